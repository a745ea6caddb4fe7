#pragma once
// Reading a cycle spec from YAML (docs/method.md §4) with every problem reported at once.

#include <filesystem>
#include <map>
#include <string>

#include "feedplan/cycles/spec.hpp"
#include "feedplan/geometry/stock.hpp"

namespace feedplan::cycles {

//! Parses and validates a cycle spec from YAML text. `source_name` names the text in problems that
//! have no field (a file name, or "test").
//!
//! Checks the structure — a mapping; known fields only (an unknown one lists the expected names);
//! required fields present; numbers, integers, strings, [x, y] points and ccw|cw where expected; a
//! `cycle` of corner|trochoid|spiral|helical_boring|pocket with its section present and no section of
//! another cycle — and then the values (validate in cycle.hpp): finite, in range, consistent. Every
//! problem found is collected; then one feedplan::InputError is thrown carrying them all, each with
//! the YAML path as field and the YAML line where known, e.g.
//! `trochoid.pitch_mm (line 7) = 12: must be in (0, 10) — ...`. Malformed YAML and an empty or
//! non-mapping document are InputErrors too. Returns a spec that generate() accepts.
CycleSpec read_cycle_spec(const std::string& yaml_text, const std::string& source_name);

//! Reads the file at `path` and parses it with read_cycle_spec (the path is the source name). A file
//! that does not exist or cannot be read is an InputError naming the path.
CycleSpec load_cycle_spec(const std::filesystem::path& path);

//! Parses a workpiece from YAML: either a document `stock: {z_bottom_mm, z_top_mm, regions: [{outer:
//! contour, holes: [contour, ...]}]}` (contours as in a cycle spec's stock: `{polygon: [[x, y], ...]}`
//! or `{circle: {center: [x, y], radius_mm: r}}`), or a whole cycle spec, whose implied (or given)
//! stock is returned. Every problem is reported at once, as read_cycle_spec does, in one InputError.
geometry::Stock read_stock_spec(const std::string& yaml_text, const std::string& source_name);

//! Reads the file at `path` with read_stock_spec; an unreadable file is an InputError naming it.
geometry::Stock load_stock_spec(const std::filesystem::path& path);

//! Parses a tool library: the end mill of every T number a program uses, each written as a cycle spec's
//! `tool` section (same fields, same checks):
//!   tools:
//!     2: {diameter_mm: 6.35, flutes: 2, helix_deg: 30, name: "1/4 in 2-flute"}
//! A tool without a name is named "T<number>". Every problem at once, in one InputError.
std::map<int, geometry::Tool> read_tool_library(const std::string& yaml_text, const std::string& source_name);

//! Reads the file at `path` with read_tool_library.
std::map<int, geometry::Tool> load_tool_library(const std::filesystem::path& path);

}  // namespace feedplan::cycles
