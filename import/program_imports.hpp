// Each program's INPT.inp lines to a spec (inpt_import.cpp picks the program).
#pragma once

#include <vector>

#include "import/inpt_import.hpp"
#include "legacy/inpt_file.hpp"

namespace dem::import {

void import_pdem_egd(const std::vector<legacy::InptLine>& lines, const ImportOptions& options, Imported& out);
void import_ballastdem(const std::vector<legacy::InptLine>& lines, const ImportOptions& options, Imported& out);

}  // namespace dem::import
