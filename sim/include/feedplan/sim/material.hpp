#pragma once
// Workpiece materials as data: a YAML library (data/materials.yaml) of named materials, each with its
// mechanistic cutting coefficients (docs/method.md §6.1, §6.2) and where those numbers come from. The
// virtual machine takes its coefficients from here; nothing in the code knows a material by name.
//
// File format (one YAML document):
//
//   materials:
//     - name: Al7075-T6                     # canonical name, unique
//       aliases: ["7075-T6", A7075]          # optional; other names that find this material
//       description: aluminium alloy, ...    # free text
//       source: Altintas, ...                # required: where the numbers come from
//       coefficients:                        # all six required, each finite and ≥ 0 (ktc > 0)
//         {ktc_n_per_mm2: 796, krc_n_per_mm2: 169, kac_n_per_mm2: 222,
//          kte_n_per_mm: 27.7, kre_n_per_mm: 30.8, kae_n_per_mm: 1.4}
//       size_effect: {exponent: 0.13, reference_chip_mm: 0.1}   # optional (min_chip_mm optional too)
//       sources: {krc_n_per_mm2: "0.3 × ktc, docs/method.md §6.2"}     # optional per-number sources
//
// Names and aliases are matched case-insensitively and must be unique across the whole library.

#include <map>
#include <string>
#include <vector>

#include "feedplan/core/input_error.hpp"
#include "feedplan/sim/cutting_coefficients.hpp"

namespace feedplan::sim {

//! One workpiece material with its cutting coefficients.
struct Material {
  std::string name;                  //!< canonical name, e.g. "S50C"
  std::vector<std::string> aliases;  //!< other names for the same entry, e.g. "1045", "C45"
  std::string description;           //!< what the material is, free text
  CuttingCoefficients coefficients;  //!< mechanistic coefficients (N/mm², N/mm) and size effect
  std::string source;                //!< where the numbers come from, for the material as a whole
  //! Where single numbers come from when that differs from `source`; keyed by the YAML field name
  //! ("krc_n_per_mm2", "size_effect", ...).
  std::map<std::string, std::string> coefficient_sources;
};

//! A set of materials, searchable by name or alias.
struct MaterialLibrary {
  std::vector<Material> materials;  //!< in file order
  std::string source_name;          //!< the file (or text) the library was read from, for messages

  //! The material whose name or one of whose aliases equals `name`, ignoring ASCII case (leading and
  //! trailing blanks ignored too), or nullptr when there is none.
  const Material* find(const std::string& name) const;

  //! The material called `name` (as find does). When there is none, throws feedplan::InputError with
  //! unknown_material_problem(*this, name, field).
  const Material& get(const std::string& name, const std::string& field = "material") const;
};

//! The problem to report when `name` (given in `field`, e.g. "material" or "spec.material (line 3)")
//! is not in `library`: `= "S55C": unknown material; known: Al7075-T6 (7075-T6, ...), S50C (1045, C45,
//! ...), ... (did you mean S50C?)`. The suggestion is the closest name or alias by edit distance,
//! offered when it is within 3 edits (or a case-insensitive prefix match); none otherwise.
InputProblem unknown_material_problem(const MaterialLibrary& library, const std::string& name,
                                      const std::string& field = "material");

//! Parses and validates a material library from YAML text; `source_name` names the text in messages
//! (a path, or "test").
//!
//! Checks the structure — a mapping with `materials:`, a non-empty list of mappings with known fields
//! only (an unknown one lists the expected names and suggests the closest); required fields present
//! (name, source, coefficients with all six values); numbers, texts and lists of texts where expected —
//! and the values: every coefficient finite and ≥ 0, ktc_n_per_mm2 > 0; size_effect.exponent in
//! [0, 1), reference_chip_mm > 0, min_chip_mm in (0, reference_chip_mm]; names non-empty; no name or
//! alias used twice (ignoring case); `sources` keys naming coefficient fields. Every problem found is
//! collected, then one feedplan::InputError carries them all, each naming the YAML path with its line
//! (`materials[1].coefficients.krc_n_per_mm2 (line 24)`), the value and the allowed range. Malformed
//! YAML and an empty document are InputErrors too. Returns the library; it is never empty.
MaterialLibrary read_materials(const std::string& yaml_text, const std::string& source_name);

//! Reads the file at `path` and parses it with read_materials (the path is the source name). A file
//! that does not exist or cannot be read is an InputError naming the path.
MaterialLibrary load_materials(const std::string& path);

}  // namespace feedplan::sim
