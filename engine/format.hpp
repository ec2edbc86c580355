// Result sets as text: an aligned table for people, CSV and JSON for programs.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "model/result.hpp"

namespace smql {

std::string valueText(const Value& value);
nlohmann::ordered_json valueJson(const Value& value);
// {"id": 12, "category": "sofa", "box": {"center": [...], "size": [...], "yaw": 0.0}, ...}
nlohmann::ordered_json rowJson(const ResultSet& result, std::size_t row);
// {"columns": [...], "rows": [{...}], "message": "..."}
nlohmann::ordered_json resultJson(const ResultSet& result);
// JSON text, compact. Text that is not UTF-8 (a database written before
// imports checked it) comes out with U+FFFD in place of the bad bytes instead
// of failing the whole answer.
std::string jsonText(const nlohmann::ordered_json& value);
std::string jsonText(const nlohmann::json& value);
std::string formatTable(const ResultSet& result);
std::string formatCsv(const ResultSet& result);

}  // namespace smql
