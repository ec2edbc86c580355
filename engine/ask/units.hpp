// Units of length a question may name, however it writes them ("cm", "centimetres", "(in
// meters)", "feet"): one table that the question reader (the answer's unit, "within 3 feet of"),
// and the answer (a length in that unit) read.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace smql::ask {

struct LengthUnit {
    std::string_view symbol;  // as the answer writes it and Translation::unit holds it: "cm"
    double metres;            // one of it in metres
    int decimals;             // how the answer rounds it: 123 cm, 1.23 m
    std::string_view words;   // every way a question writes it, separated by '|'
};

// The unit a word of a question names ("centimetres" -> cm), if any. "in" (inches) is not one:
// it is a preposition far more often.
const LengthUnit* lengthUnitNamed(std::string_view word);
// The unit of a symbol (Translation::unit), metres when it is none of the table.
const LengthUnit& lengthUnit(std::string_view symbol);
// A length in a unit: "1.23 m", "123 cm", "4.1 ft".
std::string formatLength(double metres, std::string_view symbol);

}  // namespace smql::ask
