// Named sizing parameters G (paper section 5.2): name, unit, range and meaning, so that
// templates, the CLI's JSON and the documentation share one table.
#pragma once

#include <string>

namespace drape::garment {

/// One sizing parameter of a template's parameter set `Sizing` (a struct of doubles).
template <class Sizing>
struct ParameterSpec {
    const char* name;        ///< the paper's name, e.g. "l1", "alpha"
    double Sizing::*field;   ///< the member holding the value
    double min;              ///< inclusive range, in `unit`
    double max;
    const char* unit;        ///< "cm" or "deg"
    const char* meaning;     ///< one line for docs and errors
};

/// Throws drape::InvalidInput("<garment>: parameter <name> = <value> <unit> is outside
/// [<min>, <max>] <unit> (<meaning>)") when the value is not finite or out of range.
void check_parameter(const std::string& garment, const char* name, double value, double min,
                     double max, const char* unit, const char* meaning);

/// Checks every parameter of `sizing` against its table entry (see check_parameter).
template <class Sizing, class Table>
void check_parameters(const std::string& garment, const Sizing& sizing, const Table& table) {
    for (const auto& p : table)
        check_parameter(garment, p.name, sizing.*(p.field), p.min, p.max, p.unit, p.meaning);
}

}  // namespace drape::garment
