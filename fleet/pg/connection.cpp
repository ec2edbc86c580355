#include "fleet/pg/connection.hpp"

#include <charconv>
#include <utility>

#include <fmt/format.h>
#include <libpq-fe.h>

#include "model/error.hpp"

namespace smql::fleet::pg {

namespace {

template <typename Number>
Number parsed(std::string_view text) {
    Number value{};
    std::from_chars(text.data(), text.data() + text.size(), value);
    return value;
}

int hexValue(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

std::string trimmed(std::string text) {
    while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
    return text;
}

// The URL as messages may show it: a password in it (user:secret@, password=secret) replaced.
std::string withoutPassword(std::string url) {
    if (auto scheme = url.find("://"); scheme != std::string::npos) {
        auto at = url.find('@', scheme + 3);
        auto colon = url.find(':', scheme + 3);
        if (at != std::string::npos && colon < at) url.replace(colon + 1, at - colon - 1, "***");
    }
    for (auto key = url.find("password="); key != std::string::npos; key = url.find("password=", key + 1)) {
        auto value = key + 9;
        auto end = url.find_first_of("& ", value);
        url.replace(value, (end == std::string::npos ? url.size() : end) - value, "***");
    }
    return url;
}

}  // namespace

Result::~Result() { PQclear(result_); }

Result::Result(Result&& other) noexcept : result_(std::exchange(other.result_, nullptr)) {}

int Result::rows() const { return PQntuples(result_); }

bool Result::null(int row, int column) const { return PQgetisnull(result_, row, column) != 0; }

std::string_view Result::text(int row, int column) const {
    return {PQgetvalue(result_, row, column), static_cast<std::size_t>(PQgetlength(result_, row, column))};
}

std::int64_t Result::integer(int row, int column) const { return parsed<std::int64_t>(text(row, column)); }

double Result::real(int row, int column) const { return parsed<double>(text(row, column)); }

float Result::real4(int row, int column) const { return parsed<float>(text(row, column)); }

Parameters& Parameters::add(std::string value) {
    values_.push_back(std::move(value));
    return *this;
}

Parameters& Parameters::add(std::int64_t value) { return add(fmt::format("{}", value)); }

Connection::Connection(const std::string& conninfo, std::string where)
    : pg_(PQconnectdb(conninfo.c_str())), where_(std::move(where)) {
    if (PQstatus(pg_) == CONNECTION_OK) {
        // The server's notices (an IF NOT EXISTS that found the thing) are not the user's business.
        PQsetNoticeProcessor(
            pg_, [](void*, const char*) {}, nullptr);
        return;
    }
    std::string why = withoutPassword(trimmed(PQerrorMessage(pg_)));
    PQfinish(pg_);
    throw Error(ErrorKind::Storage, fmt::format("cannot connect to the fleet store {}: {}", where_, why), std::nullopt,
                "check that the server runs and the URL's host, port, database and user are right; a password "
                "comes from the URL, ~/.pgpass or PGPASSWORD, as for psql");
}

Connection::~Connection() { PQfinish(pg_); }

void Connection::check(const Result& result, std::string_view what) {
    // A result of nullptr (out of memory, connection lost) has the status PGRES_FATAL_ERROR.
    auto status = PQresultStatus(result.result_);
    if (status == PGRES_COMMAND_OK || status == PGRES_TUPLES_OK || status == PGRES_COPY_IN) {
        lastState_.clear();
        return;
    }
    const char* state = PQresultErrorField(result.result_, PG_DIAG_SQLSTATE);
    lastState_ = state ? state : "";
    throw Error(ErrorKind::Storage,
                fmt::format("the fleet store {} failed {}: {}", where_, what, trimmed(PQerrorMessage(pg_))));
}

Result Connection::exec(std::string_view sql, std::string_view what) {
    Result r(PQexec(pg_, std::string(sql).c_str()));
    check(r, what);
    return r;
}

Result Connection::exec(std::string_view sql, const Parameters& parameters, std::string_view what) {
    std::vector<const char*> values;
    values.reserve(parameters.values_.size());
    for (const auto& v : parameters.values_) values.push_back(v.c_str());
    Result r(PQexecParams(pg_, std::string(sql).c_str(), static_cast<int>(values.size()), nullptr, values.data(),
                          nullptr, nullptr, 0));
    check(r, what);
    return r;
}

void Connection::copyIn(std::string_view copySql, std::string_view rows, std::string_view what) {
    exec(copySql, what);
    if (!rows.empty() && PQputCopyData(pg_, rows.data(), static_cast<int>(rows.size())) != 1)
        throw Error(ErrorKind::Storage,
                    fmt::format("the fleet store {} failed {}: {}", where_, what, trimmed(PQerrorMessage(pg_))));
    if (PQputCopyEnd(pg_, nullptr) != 1)
        throw Error(ErrorKind::Storage,
                    fmt::format("the fleet store {} failed {}: {}", where_, what, trimmed(PQerrorMessage(pg_))));
    Result r(PQgetResult(pg_));
    while (PGresult* rest = PQgetResult(pg_)) PQclear(rest);
    check(r, what);
}

UrlParts urlParts(const std::string& url) {
    bool isUrl = url.rfind("postgresql://", 0) == 0 || url.rfind("postgres://", 0) == 0;
    char* why = nullptr;
    PQconninfoOption* options = PQconninfoParse(url.c_str(), &why);
    if (!options || (!isUrl && url.find('=') == std::string::npos)) {
        // libpq's reason may quote the URL whole: its password masked too.
        std::string reason =
            why ? withoutPassword(trimmed(why)) : "it is neither a postgresql:// URL nor key=value pairs";
        PQfreemem(why);
        PQconninfoFree(options);
        throw Error(ErrorKind::Usage, fmt::format("'{}' is not a fleet store URL: {}", withoutPassword(url), reason),
                    std::nullopt,
                    "write it as postgresql://USER@HOST:PORT/DATABASE (a password, when one is needed, from "
                    "~/.pgpass or PGPASSWORD)");
    }
    UrlParts out;
    for (PQconninfoOption* o = options; o->keyword; ++o) {
        std::string_view key = o->keyword;
        std::string value = o->val ? o->val : "";
        if (key == "host") out.host = value;
        if (key == "port") out.port = value;
        if (key == "dbname") out.database = value;
        if (key == "user") out.user = value;
    }
    PQconninfoFree(options);
    return out;
}

std::string describeUrl(const std::string& url) {
    UrlParts parts = urlParts(url);
    std::string out = fmt::format("database {} on {}", parts.database.empty() ? "(the user's)" : parts.database,
                                  parts.host.empty() ? "the local socket" : "host " + parts.host);
    if (!parts.port.empty()) out += ":" + parts.port;
    if (!parts.user.empty()) out += " as user " + parts.user;
    return out;
}

void appendCopyText(std::string& out, std::string_view text) {
    for (char c : text) {
        switch (c) {
            case '\\':
                out += "\\\\";
                break;
            case '\t':
                out += "\\t";
                break;
            case '\n':
                out += "\\n";
                break;
            case '\r':
                out += "\\r";
                break;
            default:
                out += c;
        }
    }
}

void appendCopyBytes(std::string& out, std::string_view bytes) {
    static constexpr char kHex[] = "0123456789abcdef";
    out += "\\\\x";
    for (unsigned char c : bytes) {
        out += kHex[c >> 4];
        out += kHex[c & 15];
    }
}

std::string decodeBytea(std::string_view text) {
    if (text.substr(0, 2) != "\\x")
        throw Error(ErrorKind::Storage, "the fleet store sent a bytea value not in hex (bytea_output must be hex)");
    std::string out;
    out.reserve((text.size() - 2) / 2);
    for (std::size_t i = 2; i + 1 < text.size(); i += 2)
        out += static_cast<char>(hexValue(text[i]) * 16 + hexValue(text[i + 1]));
    return out;
}

std::string quoted(std::string_view text) {
    std::string out = "'";
    for (char c : text) {
        if (c == '\'') out += '\'';
        out += c;
    }
    return out + "'";
}

}  // namespace smql::fleet::pg
