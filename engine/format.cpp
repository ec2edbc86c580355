#include "engine/format.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "model/geometry.hpp"

namespace smql {

std::string valueText(const Value& value) {
    switch (typeOf(value)) {
        case ValueType::Null:
            return "";
        case ValueType::Integer:
            return std::to_string(std::get<std::int64_t>(value));
        case ValueType::Real:
            return fmt::format("{:.3f}", std::get<double>(value));
        case ValueType::Text:
            return std::get<std::string>(value);
        case ValueType::Box: {
            const auto& b = std::get<model::Box>(value);
            // Whole degrees, a turn a hair under zero written 0, not -0.
            const double yaw = std::round(b.yaw / model::kDegree) + 0.0;
            return fmt::format("({:.2f}, {:.2f}, {:.2f}) {:.2f}x{:.2f}x{:.2f} yaw {:.0f}", b.center.x, b.center.y,
                               b.center.z, b.size.x, b.size.y, b.size.z, yaw);
        }
    }
    return "";
}

nlohmann::ordered_json valueJson(const Value& value) {
    switch (typeOf(value)) {
        case ValueType::Null:
            return nullptr;
        case ValueType::Integer:
            return std::get<std::int64_t>(value);
        case ValueType::Real:
            return std::get<double>(value);
        case ValueType::Text:
            return std::get<std::string>(value);
        case ValueType::Box: {
            const auto& b = std::get<model::Box>(value);
            return {{"center", {b.center.x, b.center.y, b.center.z}},
                    {"size", {b.size.x, b.size.y, b.size.z}},
                    {"yaw", b.yaw}};
        }
    }
    return nullptr;
}

nlohmann::ordered_json rowJson(const ResultSet& result, std::size_t row) {
    nlohmann::ordered_json out = nlohmann::ordered_json::object();
    for (std::size_t c = 0; c < result.columns.size(); ++c)
        out[result.columns[c].name] = valueJson(result.rows[row][c]);
    return out;
}

nlohmann::ordered_json resultJson(const ResultSet& result) {
    nlohmann::ordered_json columns = nlohmann::ordered_json::array();
    for (const auto& c : result.columns) columns.push_back(c.name);
    nlohmann::ordered_json rows = nlohmann::ordered_json::array();
    for (std::size_t r = 0; r < result.rows.size(); ++r) rows.push_back(rowJson(result, r));
    nlohmann::ordered_json out = {{"columns", columns}, {"rows", rows}};
    if (!result.message.empty()) out["message"] = result.message;
    return out;
}

std::string jsonText(const nlohmann::ordered_json& value) {
    return value.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
}

std::string jsonText(const nlohmann::json& value) {
    return value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

std::string formatTable(const ResultSet& result) {
    if (result.columns.empty()) return {};
    std::vector<std::size_t> width(result.columns.size());
    std::vector<std::vector<std::string>> cells;
    for (std::size_t c = 0; c < result.columns.size(); ++c) width[c] = result.columns[c].name.size();
    for (const auto& row : result.rows) {
        auto& line = cells.emplace_back();
        for (std::size_t c = 0; c < row.size(); ++c) {
            line.push_back(valueText(row[c]));
            width[c] = std::max(width[c], line.back().size());
        }
    }
    auto emit = [&](const std::vector<std::string>& line) {
        std::string out;
        for (std::size_t c = 0; c < line.size(); ++c) {
            bool last = c + 1 == line.size();
            out += last ? line[c] : fmt::format("{:<{}}  ", line[c], width[c]);
        }
        return out + "\n";
    };
    std::vector<std::string> header;
    for (const auto& c : result.columns) header.push_back(c.name);
    std::string out = emit(header);
    std::vector<std::string> rule;
    for (std::size_t c = 0; c < width.size(); ++c) rule.push_back(std::string(width[c], '-'));
    out += emit(rule);
    for (const auto& line : cells) out += emit(line);
    return out;
}

std::string formatCsv(const ResultSet& result) {
    auto quote = [](const std::string& cell) {
        if (cell.find_first_of(",\"\n") == std::string::npos) return cell;
        std::string out = "\"";
        for (char ch : cell) out += ch == '"' ? std::string("\"\"") : std::string(1, ch);
        return out + "\"";
    };
    std::string out;
    for (std::size_t c = 0; c < result.columns.size(); ++c) out += (c ? "," : "") + quote(result.columns[c].name);
    out += "\n";
    for (const auto& row : result.rows) {
        for (std::size_t c = 0; c < row.size(); ++c) {
            std::string cell = typeOf(row[c]) == ValueType::Box ? jsonText(valueJson(row[c])) : valueText(row[c]);
            out += (c ? "," : "") + quote(cell);
        }
        out += "\n";
    }
    return out;
}

}  // namespace smql
