// libpq behind our own types: a connection, a result, COPY and parameters. Every failure is an
// smql::Error(Storage) that says what was being done and what the server said; libpq types stay in
// fleet/.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

struct pg_conn;
struct pg_result;

namespace smql::fleet::pg {

class Result {
public:
    explicit Result(pg_result* result) : result_(result) {}
    ~Result();
    Result(const Result&) = delete;
    Result& operator=(const Result&) = delete;
    Result(Result&& other) noexcept;
    Result& operator=(Result&&) = delete;

    int rows() const;
    bool null(int row, int column) const;
    std::string_view text(int row, int column) const;
    std::int64_t integer(int row, int column) const;
    double real(int row, int column) const;
    float real4(int row, int column) const;

private:
    friend class Connection;
    pg_result* result_;
};

// Parameters as text: numbers in their shortest exact form, so the server reads the same value.
class Parameters {
public:
    Parameters& add(std::string value);
    Parameters& add(std::int64_t value);

private:
    friend class Connection;
    std::vector<std::string> values_;
};

class Connection {
public:
    // `where` names the server in messages (a URL without its password). Throws when the server
    // cannot be reached or refuses the login, with libpq's reason.
    Connection(const std::string& conninfo, std::string where);
    ~Connection();
    Connection(const Connection&) = delete;
    Connection& operator=(const Connection&) = delete;

    // Runs statements without parameters (several, separated by ';'); `what` names the work in errors.
    Result exec(std::string_view sql, std::string_view what);
    Result exec(std::string_view sql, const Parameters& parameters, std::string_view what);
    // COPY ... FROM STDIN with `rows` in COPY's text format.
    void copyIn(std::string_view copySql, std::string_view rows, std::string_view what);

    const std::string& where() const { return where_; }
    // SQLSTATE of the last failed statement ("" when none), to tell a permission error from others.
    const std::string& lastState() const { return lastState_; }

private:
    void check(const Result& result, std::string_view what);
    pg_conn* pg_ = nullptr;
    std::string where_;
    std::string lastState_;
};

// What a URL names (empty: libpq's default), for a sharded store's foreign servers.
struct UrlParts {
    std::string host, port, database, user;
};
// Throws smql::Error(Usage) when libpq cannot read the URL (the message never shows a password).
UrlParts urlParts(const std::string& url);

// A fleet store's URL (postgresql://user@host:port/database?options, or libpq's key=value form)
// checked and named for messages without its password: "database fleet on host db1:5432 as
// user robot". Throws smql::Error(Usage) when libpq cannot read it.
std::string describeUrl(const std::string& url);

// COPY's text format: backslash, tab and line ends escaped (\N is NULL, written by the caller).
void appendCopyText(std::string& out, std::string_view text);
// A bytea value in COPY's text format: \\x and the bytes in hex.
void appendCopyBytes(std::string& out, std::string_view bytes);
// A bytea value as the server returns it in text (\x followed by hex) -> the bytes.
std::string decodeBytea(std::string_view text);
// A literal SQL string, quoted ('it''s'), for the few statements that take no parameters (DDL).
std::string quoted(std::string_view text);

}  // namespace smql::fleet::pg
