// The pelage command line: one file per command, each adding itself to the CLI11 app with the
// shared option groups of options.h.
#pragma once

#include <CLI/CLI.hpp>

#include "pelage/fur/coverage.h"

namespace pelage::app {

void addInfoCommand(CLI::App& app);
void addSkinCommand(CLI::App& app);
void addHairCommand(CLI::App& app);
void addBenchCommand(CLI::App& app);
void addExportCommand(CLI::App& app);
void addAnalyzeCommand(CLI::App& app);
void addGroomCommand(CLI::App& app);
// `pelage view` and `pelage render` exist only with the viewer (PELAGE_BUILD_VIEWER).
void addViewCommand(CLI::App& app);
void addRenderCommand(CLI::App& app);

// Prints the fur's density and optical depth per coat and the expected share of skin hidden
// (`pelage info` and `pelage hair`).
void printCoverage(const fur::FurCoverage& coverage);

}  // namespace pelage::app
