#pragma once
// A materials file for the CLI tests that cut on a machine 40 % harder than the model: the bundled S50C
// (data/materials.yaml: ktc 2000, krc 600, kac 500, kte 20, kre 20, kae 2) × 1.4, every coefficient.

namespace feedplan::cli_test {

inline constexpr const char* kHardS50C =
    "materials:\n"
    "  - name: S50C\n"
    "    source: the bundled S50C × 1.4 (a machine 40 % harder than the model)\n"
    "    coefficients:\n"
    "      ktc_n_per_mm2: 2800\n"
    "      krc_n_per_mm2: 840\n"
    "      kac_n_per_mm2: 700\n"
    "      kte_n_per_mm: 28\n"
    "      kre_n_per_mm: 28\n"
    "      kae_n_per_mm: 2.8\n";

}  // namespace feedplan::cli_test
