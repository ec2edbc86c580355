#include "shell/output.hpp"

#include <algorithm>
#include <array>
#include <numeric>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "engine/format.hpp"
#include "model/error.hpp"

namespace smql::shell {

namespace {

// A mode's first name is the one it is shown by; `column` is sqlite3's name for the aligned columns
// smql calls table.
constexpr std::array<std::pair<std::string_view, OutputMode>, 11> kModes{{
    {"table", OutputMode::Table},
    {"column", OutputMode::Table},
    {"box", OutputMode::Box},
    {"markdown", OutputMode::Markdown},
    {"csv", OutputMode::Csv},
    {"tsv", OutputMode::Tsv},
    {"list", OutputMode::List},
    {"line", OutputMode::Line},
    {"json", OutputMode::Json},
    {"jsonl", OutputMode::Jsonl},
    {"html", OutputMode::Html},
}};

// Text for a person's screen: a control byte other than a line break or a tab (an escape sequence in
// a name an imported file gave) is shown as \xNN, never sent raw to the terminal, as errors do.
std::string printable(std::string_view text) {
    std::string out;
    for (char c : text) {
        const auto byte = static_cast<unsigned char>(c);
        if ((byte < 0x20 && c != '\n' && c != '\t') || byte == 0x7f)
            out += fmt::format("\\x{:02X}", byte);
        else
            out += c;
    }
    return out;
}

// A cell as text: boxes as their JSON in csv and tsv, where a program reads them back; a null as
// .nullvalue says; control bytes shown as \xNN (json and jsonl keep every byte, escaped as JSON
// escapes them).
std::string cellText(const Value& value, bool boxAsJson, const OutputOptions& options) {
    if (typeOf(value) == ValueType::Null) return printable(options.nullValue);
    return boxAsJson && typeOf(value) == ValueType::Box ? valueJson(value).dump() : printable(valueText(value));
}

bool isContinuationByte(char c) { return (static_cast<unsigned char>(c) & 0xC0) == 0x80; }

// The first `width` columns of `text`, ending in an ellipsis when something was cut.
std::string fit(const std::string& text, std::size_t width) {
    if (displayWidth(text) <= width) return text;
    if (width == 0) return {};
    std::size_t keep = width - 1, columns = 0, end = 0;
    for (; end < text.size(); ++end) {
        if (isContinuationByte(text[end])) continue;
        if (columns == keep) break;
        ++columns;
    }
    return text.substr(0, end) + "…";
}

std::string padded(const std::string& text, std::size_t width) {
    return text + std::string(width - std::min(width, displayWidth(text)), ' ');
}

// Column widths that fit `available` columns of text: the widest columns give way first, down to a
// few characters each (beyond that the lines wrap rather than lose every cell).
std::vector<std::size_t> fitWidths(std::vector<std::size_t> widths, std::size_t available) {
    constexpr std::size_t kNarrowest = 4;
    auto total = [&](std::size_t cap) {
        std::size_t sum = 0;
        for (std::size_t w : widths) sum += std::min(w, cap);
        return sum;
    };
    std::size_t widest = widths.empty() ? 0 : *std::max_element(widths.begin(), widths.end());
    if (total(widest) <= available) return widths;
    std::size_t low = kNarrowest, high = widest;  // the largest cap that fits lies in [low, high)
    if (total(low) > available) high = low;
    while (low + 1 < high) {
        std::size_t middle = (low + high) / 2;
        (total(middle) <= available ? low : high) = middle;
    }
    for (std::size_t& w : widths) w = std::min(w, low);
    return widths;
}

struct Grid {
    std::vector<std::string> header;
    std::vector<std::vector<std::string>> rows;
    std::vector<std::size_t> widths;
};

Grid gridOf(const ResultSet& result, const OutputOptions& options) {
    Grid grid;
    for (const auto& c : result.columns) grid.header.push_back(c.name), grid.widths.push_back(displayWidth(c.name));
    for (const auto& row : result.rows) {
        auto& line = grid.rows.emplace_back();
        for (std::size_t c = 0; c < row.size(); ++c) {
            line.push_back(cellText(row[c], false, options));
            grid.widths[c] = std::max(grid.widths[c], displayWidth(line.back()));
        }
    }
    return grid;
}

std::string footer(const ResultSet& result) {
    if (!result.message.empty()) return printable(result.message) + "\n";
    if (result.columns.empty()) return {};
    return fmt::format("({} row{})\n", result.rows.size(), result.rows.size() == 1 ? "" : "s");
}

std::string table(const ResultSet& result, const OutputOptions& options) {
    if (result.columns.empty()) return footer(result);
    Grid grid = gridOf(result, options);
    const std::size_t gaps = 2 * (grid.widths.size() - 1);
    if (options.maxWidth > gaps) grid.widths = fitWidths(grid.widths, options.maxWidth - 1 - gaps);
    auto line = [&](const std::vector<std::string>& cells) {
        std::string out;
        for (std::size_t c = 0; c < cells.size(); ++c) {
            std::string cell = fit(cells[c], grid.widths[c]);
            out += c + 1 == cells.size() ? cell : padded(cell, grid.widths[c]) + "  ";
        }
        return out + "\n";
    };
    std::string out;
    if (options.headers) {
        out += line(grid.header);
        std::vector<std::string> rule;
        for (std::size_t w : grid.widths) rule.emplace_back(w, '-');
        out += line(rule);
    }
    for (const auto& row : grid.rows) out += line(row);
    return out + footer(result);
}

std::string box(const ResultSet& result, const OutputOptions& options) {
    if (result.columns.empty()) return footer(result);
    Grid grid = gridOf(result, options);
    const std::size_t frame = 3 * grid.widths.size() + 1;
    if (options.maxWidth > frame) grid.widths = fitWidths(grid.widths, options.maxWidth - 1 - frame);
    auto rule = [&](std::string_view left, std::string_view middle, std::string_view right) {
        std::string out(left);
        for (std::size_t c = 0; c < grid.widths.size(); ++c) {
            for (std::size_t i = 0; i < grid.widths[c] + 2; ++i) out += "─";
            out += c + 1 == grid.widths.size() ? right : middle;
        }
        return out + "\n";
    };
    auto line = [&](const std::vector<std::string>& cells) {
        std::string out = "│";
        for (std::size_t c = 0; c < cells.size(); ++c)
            out += " " + padded(fit(cells[c], grid.widths[c]), grid.widths[c]) + " │";
        return out + "\n";
    };
    std::string out = rule("┌", "┬", "┐");
    if (options.headers) out += line(grid.header) + rule("├", "┼", "┤");
    for (const auto& row : grid.rows) out += line(row);
    return out + rule("└", "┴", "┘") + footer(result);
}

// Markdown keeps every character, for pasting into documents: no cell is cut to the terminal.
std::string markdown(const ResultSet& result, const OutputOptions& options) {
    if (result.columns.empty()) return footer(result);
    Grid grid = gridOf(result, options);
    auto escape = [](std::string& cell) {
        std::string out;
        for (char ch : cell)
            out += ch == '|' ? std::string("\\|") : ch == '\n' ? std::string("<br>") : std::string(1, ch);
        cell = std::move(out);
    };
    // Markdown needs a header row to be a table; with headers off its cells stay empty.
    if (!options.headers) std::fill(grid.header.begin(), grid.header.end(), std::string());
    std::fill(grid.widths.begin(), grid.widths.end(), 3);  // a rule needs three dashes
    auto measure = [&](std::vector<std::string>& cells) {
        for (std::size_t c = 0; c < cells.size(); ++c)
            escape(cells[c]), grid.widths[c] = std::max(grid.widths[c], displayWidth(cells[c]));
    };
    measure(grid.header);
    for (auto& row : grid.rows) measure(row);
    auto line = [&](const std::vector<std::string>& cells) {
        std::string out = "|";
        for (std::size_t c = 0; c < cells.size(); ++c) out += " " + padded(cells[c], grid.widths[c]) + " |";
        return out + "\n";
    };
    std::string out = line(grid.header) + "|";
    for (std::size_t w : grid.widths) out += std::string(w + 2, '-') + "|";
    out += "\n";
    for (const auto& row : grid.rows) out += line(row);
    // No row count: what is pasted is the table.
    return out + (result.message.empty() ? "" : printable(result.message) + "\n");
}

std::string delimited(const ResultSet& result, const OutputOptions& options, char separator) {
    if (result.columns.empty()) return {};
    auto escape = [&](const std::string& cell) {
        std::string out;
        if (separator == ',') {  // RFC 4180: quote a cell holding a comma, a quote or a line break
            if (cell.find_first_of(",\"\r\n") == std::string::npos) return cell;
            out = "\"";
            for (char ch : cell) out += ch == '"' ? std::string("\"\"") : std::string(1, ch);
            return out + "\"";
        }
        // TSV has no quoting: tabs, line breaks and backslashes are escaped, so a row stays one line.
        for (char ch : cell) {
            switch (ch) {
                case '\t':
                    out += "\\t";
                    break;
                case '\n':
                    out += "\\n";
                    break;
                case '\r':
                    out += "\\r";
                    break;
                case '\\':
                    out += "\\\\";
                    break;
                default:
                    out += printable(std::string_view(&ch, 1));
            }
        }
        return out;
    };
    std::string out;
    auto line = [&](auto&& cellOf) {
        for (std::size_t c = 0; c < result.columns.size(); ++c)
            out += (c ? std::string(1, separator) : "") + escape(cellOf(c));
        out += "\n";
    };
    if (options.headers) line([&](std::size_t c) { return result.columns[c].name; });
    for (const auto& row : result.rows) line([&](std::size_t c) { return cellText(row[c], true, options); });
    return out;
}

// sqlite3's list mode: the values as they are, the separator between them.
std::string list(const ResultSet& result, const OutputOptions& options) {
    if (result.columns.empty()) return result.message.empty() ? "" : printable(result.message) + "\n";
    std::string out;
    auto line = [&](auto&& cellOf) {
        for (std::size_t c = 0; c < result.columns.size(); ++c) out += (c ? options.separator : "") + cellOf(c);
        out += "\n";
    };
    if (options.headers) line([&](std::size_t c) { return result.columns[c].name; });
    for (const auto& row : result.rows) line([&](std::size_t c) { return cellText(row[c], false, options); });
    return out + (result.message.empty() ? "" : printable(result.message) + "\n");
}

// sqlite3's line mode: one "name = value" line per column, the names right-aligned, a blank line
// between rows.
std::string lines(const ResultSet& result, const OutputOptions& options) {
    std::size_t width = 0;
    for (const auto& c : result.columns) width = std::max(width, displayWidth(c.name));
    std::string out;
    for (std::size_t r = 0; r < result.rows.size(); ++r) {
        if (r) out += "\n";
        for (std::size_t c = 0; c < result.columns.size(); ++c)
            out += fmt::format("{:>{}} = {}\n", result.columns[c].name, width,
                               cellText(result.rows[r][c], false, options));
    }
    return out + (result.message.empty() ? "" : (out.empty() ? "" : "\n") + printable(result.message) + "\n");
}

// sqlite3's html mode: the rows of an HTML table, for pasting into a page's <table>.
std::string html(const ResultSet& result, const OutputOptions& options) {
    auto escape = [](const std::string& cell) {
        std::string out;
        for (char ch : cell) {
            switch (ch) {
                case '<':
                    out += "&lt;";
                    break;
                case '>':
                    out += "&gt;";
                    break;
                case '&':
                    out += "&amp;";
                    break;
                case '"':
                    out += "&quot;";
                    break;
                case '\'':
                    out += "&#39;";
                    break;
                default:
                    out += ch;
            }
        }
        return out;
    };
    std::string out;
    auto row = [&](std::string_view tag, auto&& cellOf) {
        out += "<TR>";
        for (std::size_t c = 0; c < result.columns.size(); ++c)
            out += fmt::format("<{0}>{1}</{0}>\n", tag, escape(cellOf(c)));
        out += "</TR>\n";
    };
    if (!result.columns.empty() && options.headers) row("TH", [&](std::size_t c) { return result.columns[c].name; });
    for (const auto& r : result.rows) row("TD", [&](std::size_t c) { return cellText(r[c], false, options); });
    return out + (result.message.empty() ? "" : printable(result.message) + "\n");
}

}  // namespace

OutputMode parseOutputMode(std::string_view name) {
    for (const auto& [modeName, mode] : kModes)
        if (modeName == name) return mode;
    throw Error(ErrorKind::Usage, fmt::format("unknown output mode '{}'", name), std::nullopt,
                fmt::format("modes: {}", fmt::join(outputModeNames(), ", ")));
}

std::vector<std::string> outputModeNames() {
    std::vector<std::string> names;
    for (const auto& entry : kModes) names.emplace_back(entry.first);
    return names;
}

std::string_view toString(OutputMode mode) {
    for (const auto& [modeName, m] : kModes)
        if (m == mode) return modeName;
    return "table";
}

std::size_t displayWidth(std::string_view text) {
    return static_cast<std::size_t>(
        std::count_if(text.begin(), text.end(), [](char c) { return !isContinuationByte(c); }));
}

std::string renderResult(const ResultSet& result, const OutputOptions& options) {
    switch (options.mode) {
        case OutputMode::Table:
            return table(result, options);
        case OutputMode::Box:
            return box(result, options);
        case OutputMode::Markdown:
            return markdown(result, options);
        case OutputMode::Csv:
            return delimited(result, options, ',');
        case OutputMode::Tsv:
            return delimited(result, options, '\t');
        case OutputMode::List:
            return list(result, options);
        case OutputMode::Line:
            return lines(result, options);
        case OutputMode::Html:
            return html(result, options);
        case OutputMode::Json:
        case OutputMode::Jsonl:
            return jsonText(resultJson(result)) + "\n";
    }
    return {};
}

}  // namespace smql::shell
