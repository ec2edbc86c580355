// Result sets as the shell prints them, in the output modes sqlite3 users know.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "model/result.hpp"

namespace smql::shell {

enum class OutputMode { Table, Box, Markdown, Csv, Tsv, List, Line, Json, Jsonl, Html };

// table (or column), box, markdown, csv, tsv, list, line, json, jsonl, html; throws Error(Usage)
// for another name.
OutputMode parseOutputMode(std::string_view name);
std::string_view toString(OutputMode mode);
// Every mode's name, for options, hints and completion.
std::vector<std::string> outputModeNames();

struct OutputOptions {
    OutputMode mode = OutputMode::Table;
    bool headers = true;          // column names in table, box, markdown, csv, tsv and list
    std::size_t maxWidth = 0;     // table and box lines fit in this many columns (0: no limit)
    std::string separator = "|";  // between the values of list mode (sqlite3's -separator)
    std::string nullValue;        // what a null prints as (sqlite3's .nullvalue; json keeps null)
};

// One result in a text mode (not json, whose framing is the session's): the rows, then for table,
// box and markdown the statement's sentence or the row count. Empty for a result csv and tsv have
// nothing to say about (a statement without columns, such as SET).
std::string renderResult(const ResultSet& result, const OutputOptions& options);

// Columns a string takes on a terminal: UTF-8 code points, each one column wide.
std::size_t displayWidth(std::string_view text);

}  // namespace smql::shell
