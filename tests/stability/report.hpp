// The stability suite's outputs: a table on stdout, and stability.csv,
// stability.json and stability.svg (p99 relative t error against ns per ray).
#pragma once

#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "measure.hpp"

namespace prism::stability {

// A backend that did not run, and why.
struct Skipped {
  std::string backend, reason;
  bool required = false;  // in PRISM_REQUIRE_BACKENDS: a failure, not a skip
};

// "3.2e-12", "0" or "-" (no values).
std::string format_error(const Percentiles& p, double Percentiles::*field);

void print_table(std::FILE* out, const std::vector<Summary>& rows);

// One row per summary, every number.
void write_csv(const std::filesystem::path& file, const std::vector<Summary>& rows);
nlohmann::ordered_json summary_json(const Summary& s);
// `meta`: mode, run times, skipped backends, ...; `sweep`: the rows per
// parameter value (full mode), under "sweep".
void write_json(const std::filesystem::path& file, const nlohmann::ordered_json& meta, const std::vector<Summary>& rows,
                const std::vector<Summary>& sweep);
// p99 relative t error (log y) against ns per ray (log x): one colour per
// backend, one point per row.
void write_svg(const std::filesystem::path& file, const std::vector<Summary>& rows, const std::string& title);

}  // namespace prism::stability
