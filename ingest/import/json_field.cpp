#include "ingest/import/json_field.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include <fmt/format.h>

#include "ingest/import/common.hpp"
#include "model/error.hpp"
#include "model/utf8.hpp"

namespace smql::import::detail {

namespace {

// nlohmann's messages start with "[json.exception.x.n] parse error at line L, column C: ";
// the location is reported our way, so keep only the reason.
// The text it quotes ("last read: ...") is the file's raw bytes, which need
// not be UTF-8.
std::string reasonOf(const std::string& what) {
    std::size_t column = what.find("column ");
    std::size_t colon = what.find(": ", column == std::string::npos ? 0 : column);
    if (colon != std::string::npos) return model::escapeInvalidUtf8(what.substr(colon + 2));
    std::size_t bracket = what.find("] ");
    return model::escapeInvalidUtf8(bracket == std::string::npos ? what : what.substr(bracket + 2));
}

SourceLocation locationOfByte(const std::string& text, std::size_t byte) {
    // `byte` is 1-based and may point one past the end (unexpected end of input).
    std::size_t pos = std::min(byte == 0 ? 0 : byte - 1, text.size());
    auto begin = text.begin();
    int line = 1 + static_cast<int>(std::count(begin, begin + static_cast<std::ptrdiff_t>(pos), '\n'));
    std::size_t lineStart = 0;
    if (pos > 0) {
        std::size_t newline = text.rfind('\n', pos - 1);
        if (newline != std::string::npos) lineStart = newline + 1;
    }
    return SourceLocation{line, static_cast<int>(pos - lineStart) + 1, 1};
}

std::string describe(const Json& value) {
    switch (value.type()) {
        case Json::value_t::null:
            return "null";
        case Json::value_t::boolean:
            return "a boolean";
        case Json::value_t::string:
            return "a string";
        case Json::value_t::array:
            return fmt::format("an array of {}", value.size());
        case Json::value_t::object:
            return "an object";
        case Json::value_t::number_integer:
        case Json::value_t::number_unsigned:
        case Json::value_t::number_float:
            return "a number";
        default:
            return "an unsupported value";
    }
}

// Builds the document as nlohmann's own DOM parser does, and checks each object's keys on the way:
// a repeated key or an object of too many members is an error that names its path. (nlohmann's
// public way to see the keys, its callback parser, looks along the enclosing array at every
// object's end: quadratic in an array's length, minutes for a file of a million relations.)
class CheckedDomParser {
public:
    CheckedDomParser(Json& result, const JsonSource& source) : dom_(result), source_(&source) {}

    bool null() { return countElement(), dom_.null(); }
    bool boolean(bool value) { return countElement(), dom_.boolean(value); }
    bool number_integer(Json::number_integer_t value) { return countElement(), dom_.number_integer(value); }
    bool number_unsigned(Json::number_unsigned_t value) { return countElement(), dom_.number_unsigned(value); }
    bool number_float(Json::number_float_t value, const Json::string_t& text) {
        return countElement(), dom_.number_float(value, text);
    }
    bool string(Json::string_t& value) { return countElement(), dom_.string(value); }
    bool binary(Json::binary_t& value) { return countElement(), dom_.binary(value); }
    bool start_object(std::size_t elements) {
        countElement();
        frames_.push_back(Frame{true, {}, 0, {}});
        return dom_.start_object(elements);
    }
    bool start_array(std::size_t elements) {
        countElement();
        frames_.push_back(Frame{false, {}, 0, {}});
        return dom_.start_array(elements);
    }
    bool end_object() { return frames_.pop_back(), dom_.end_object(); }
    bool end_array() { return frames_.pop_back(), dom_.end_array(); }
    bool key(Json::string_t& key) {
        Frame& top = frames_.back();
        top.key = key;
        if (!top.keys.insert(top.key).second)
            throw Error(ErrorKind::Input,
                        fmt::format("{}: {}: key appears twice in the same object", source_->file, path()),
                        std::nullopt, source_->hint);
        // The members keep the file's order, which costs a look along the object's members
        // per member: an object of a few thousand is read in milliseconds, and more are refused.
        if (top.keys.size() > kMaxObjectMembers)
            throw Error(
                ErrorKind::Input,
                fmt::format("{}: {}: an object of more than {} members", source_->file, path(), kMaxObjectMembers),
                std::nullopt, source_->hint);
        return dom_.key(key);
    }
    template <class Exception>
    bool parse_error(std::size_t position, const std::string& token, const Exception& error) {
        return dom_.parse_error(position, token, error);  // throws it
    }

private:
    struct Frame {
        bool isObject;
        std::string key;    // member being read (objects)
        std::size_t count;  // elements started so far (arrays)
        std::set<std::string> keys;
    };

    void countElement() {
        if (!frames_.empty() && !frames_.back().isObject) ++frames_.back().count;
    }

    std::string path() const {
        std::string out;
        for (const Frame& f : frames_) {
            if (f.isObject)
                out += (out.empty() ? "" : ".") + f.key;
            else
                out += fmt::format("[{}]", f.count - 1);
        }
        return out;
    }

    nlohmann::detail::json_sax_dom_parser<Json> dom_;
    const JsonSource* source_;
    std::vector<Frame> frames_;
};

}  // namespace

Json parseJsonFile(const JsonSource& source) {
    std::string text = readTextFile(source.file, source.hint);
    if (text.find_first_not_of(" \t\r\n") == std::string::npos)
        throw Error(ErrorKind::Input, source.file + ": the file is empty", std::nullopt, source.hint);
    try {
        Json document;
        CheckedDomParser parser(document, source);
        Json::sax_parse(text, &parser);
        return document;
    } catch (const Json::parse_error& e) {
        SourceLocation where = locationOfByte(text, e.byte);
        throw Error(
            ErrorKind::Input,
            fmt::format("{}:{}:{}: not valid JSON: {}", source.file, where.line, where.column, reasonOf(e.what())),
            where, source.hint);
    } catch (const Json::exception& e) {
        // Number overflow (1e999): nlohmann gives no position for it.
        throw Error(ErrorKind::Input, fmt::format("{}: not valid JSON: {}", source.file, reasonOf(e.what())),
                    std::nullopt, source.hint);
    }
}

void Field::fail(std::string_view what) const {
    std::string message = path_.empty() ? fmt::format("{}: {}", source_->file, what)
                                        : fmt::format("{}: {}: {}", source_->file, path_, what);
    throw Error(ErrorKind::Input, std::move(message), std::nullopt, source_->hint);
}

void Field::expectObject() const {
    if (!value_->is_object()) fail("expected an object, got " + describe(*value_));
}

Field Field::at(std::string_view key) const {
    std::optional<Field> member = find(key);
    if (!member) fail(fmt::format("missing field '{}'", key));
    return *member;
}

std::optional<Field> Field::find(std::string_view key) const {
    expectObject();
    auto it = value_->find(std::string(key));
    if (it == value_->end()) return std::nullopt;
    return Field(*it, *source_, path_.empty() ? std::string(key) : path_ + "." + std::string(key));
}

void Field::allowOnly(std::initializer_list<std::string_view> keys) const {
    expectObject();
    for (const auto& [key, value] : value_->items())
        if (std::find(keys.begin(), keys.end(), key) == keys.end())
            Field(value, *source_, path_.empty() ? key : path_ + "." + key).fail("unknown field");
}

std::vector<std::pair<std::string, Field>> Field::members() const {
    expectObject();
    std::vector<std::pair<std::string, Field>> out;
    for (const auto& [key, value] : value_->items())
        out.emplace_back(key, Field(value, *source_, path_.empty() ? key : path_ + "." + key));
    return out;
}

std::size_t Field::size() const {
    if (!value_->is_array()) fail("expected an array, got " + describe(*value_));
    return value_->size();
}

Field Field::operator[](std::size_t index) const {
    return Field((*value_)[index], *source_, fmt::format("{}[{}]", path_, index));
}

double Field::number() const {
    // JSON cannot spell NaN or infinity, and the parser rejects overflowing
    // literals, so every number that arrives here is finite.
    if (!value_->is_number()) fail("expected a number, got " + describe(*value_));
    return value_->get<double>();
}

std::int64_t Field::integer() const {
    if (value_->is_number_unsigned()) {
        if (value_->get<std::uint64_t>() > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()))
            fail("integer too large");
        return static_cast<std::int64_t>(value_->get<std::uint64_t>());
    }
    if (!value_->is_number_integer()) fail("expected an integer, got " + describe(*value_));
    return value_->get<std::int64_t>();
}

std::uint64_t Field::unsignedInteger() const {
    if (value_->is_number_integer() && !value_->is_number_unsigned())
        fail(fmt::format("expected a non-negative integer, got {}", value_->get<std::int64_t>()));
    if (!value_->is_number_unsigned()) fail("expected a non-negative integer, got " + describe(*value_));
    return value_->get<std::uint64_t>();
}

std::string Field::string() const {
    if (!value_->is_string()) fail("expected a string, got " + describe(*value_));
    // A NUL in a name or a text is no character of it: it cuts the text short in C strings and is
    // refused by PostgreSQL (a fleet push would stop there for good).
    if (value_->get_ref<const std::string&>().find('\0') != std::string::npos)
        fail("a NUL character (\\u0000) in a text: names and texts hold none");
    return value_->get<std::string>();
}

bool Field::boolean() const {
    if (!value_->is_boolean()) fail("expected true or false, got " + describe(*value_));
    return value_->get<bool>();
}

std::vector<double> Field::numbers(std::size_t count) const {
    if (!value_->is_array()) fail(fmt::format("expected an array of {} numbers, got {}", count, describe(*value_)));
    if (value_->size() != count) fail(fmt::format("expected {} numbers, got {}", count, value_->size()));
    std::vector<double> out;
    for (std::size_t i = 0; i < count; ++i) out.push_back((*this)[i].number());
    return out;
}

model::Vec3 Field::vec3() const {
    std::vector<double> v = numbers(3);
    return {v[0], v[1], v[2]};
}

model::Vec3 Field::coordinates() const {
    model::Vec3 v = vec3();
    for (double c : {v.x, v.y, v.z})
        if (std::abs(c) > kMaxCoordinate)
            fail(fmt::format("coordinate {} is more than {} m from the origin", c, kMaxCoordinate));
    return v;
}

}  // namespace smql::import::detail
