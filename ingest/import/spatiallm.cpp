// SpatialLM layout text -> SceneData (docs/formats.md, "SpatialLM layout").
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <map>
#include <string_view>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "ingest/import/common.hpp"
#include "ingest/import/importers.hpp"
#include "ingest/import/viewpoint.hpp"
#include "model/category.hpp"
#include "model/error.hpp"
#include "model/utf8.hpp"

namespace smql::import {

namespace {

using detail::kMaxCoordinate;
using detail::kMaxSize;

// SpatialLM writes walls with thickness 0 (a bare segment); a plane still
// needs some extent across it.
constexpr double kDefaultWallThickness = 0.02;

// Source ids: walls keep n, doors 1000+n, windows 2000+n, bboxes 3000+n.
constexpr std::int64_t kIdBlock = 1000;
// Bbox numbers are open-ended but bounded, so 3000 + n stays a 64-bit integer (and exact in JSON readers
// that use doubles).
constexpr std::int64_t kMaxBboxNumber = 999'999'999'999;

constexpr std::string_view kSpatialLmHint =
    "SpatialLM layout lines: wall_0=Wall(ax,ay,az,bx,by,bz,height,thickness), "
    "door_0=Door(wall_0,x,y,z,width,height), window_0=Window(wall_0,x,y,z,width,height), "
    "bbox_0=Bbox(class,x,y,z,angle_z,scale_x,scale_y,scale_z)";

struct EntityType {
    std::string_view name;    // as written after '='
    std::string_view prefix;  // entity names are <prefix>_<n>
    std::vector<std::string_view> fields;
    std::int64_t idBase;
};

const std::vector<EntityType>& entityTypes() {
    static const std::vector<EntityType> types = {
        {"Wall", "wall", {"ax", "ay", "az", "bx", "by", "bz", "height", "thickness"}, 0},
        {"Door", "door", {"wall", "position_x", "position_y", "position_z", "width", "height"}, kIdBlock},
        {"Window", "window", {"wall", "position_x", "position_y", "position_z", "width", "height"}, 2 * kIdBlock},
        {"Bbox",
         "bbox",
         {"class", "position_x", "position_y", "position_z", "angle_z", "scale_x", "scale_y", "scale_z"},
         3 * kIdBlock},
    };
    return types;
}

// A piece of a line and where it starts (1-based column), for error carets.
struct Token {
    std::string_view text;
    int column = 1;
};

Token trimmed(std::string_view line, std::size_t begin, std::size_t end) {
    while (begin < end && std::isspace(static_cast<unsigned char>(line[begin]))) ++begin;
    while (end > begin && std::isspace(static_cast<unsigned char>(line[end - 1]))) --end;
    return {line.substr(begin, end - begin), static_cast<int>(begin) + 1};
}

struct WallInfo {
    double yaw;
    double thickness;
};

class LayoutParser {
public:
    explicit LayoutParser(const std::string& path) : path_(path) {}

    void parseLine(int lineNumber, std::string_view line) {
        line_ = lineNumber;
        checkText(line);
        Token whole = trimmed(line, 0, line.size());
        if (whole.text.empty() || whole.text.front() == '#') return;

        std::size_t equals = line.find('=');
        std::size_t open = line.find('(', equals == std::string_view::npos ? 0 : equals);
        std::size_t close = line.rfind(')');
        if (equals == std::string_view::npos || open == std::string_view::npos || close == std::string_view::npos ||
            close < open)
            fail(whole, "expected <name>=<Type>(<values>)");
        Token after = trimmed(line, close + 1, line.size());
        if (!after.text.empty()) fail(after, "unexpected text after ')'");

        Token name = trimmed(line, 0, equals);
        Token typeName = trimmed(line, equals + 1, open);
        const EntityType* type = nullptr;
        for (const EntityType& t : entityTypes())
            if (typeName.text == t.name) type = &t;
        if (!type)
            fail(typeName,
                 fmt::format("unknown entity type '{}' (expected Wall, Door, Window or Bbox)", typeName.text));

        std::int64_t number = entityNumber(name, *type);
        if (auto [it, fresh] = definedAt_.emplace(std::string(name.text), line_); !fresh)
            fail(name, fmt::format("duplicate name '{}' (first defined at line {})", name.text, it->second));

        std::vector<Token> args = splitArguments(line, open + 1, close);
        if (args.size() != type->fields.size())
            fail(Token{line.substr(open, close - open + 1), static_cast<int>(open) + 1},
                 fmt::format("{} takes {} values ({}), got {}", type->name, type->fields.size(),
                             fmt::join(type->fields, ", "), args.size()));

        model::Node node;
        node.id = nodes_.size() + 1;
        node.sourceId = type->idBase + number;
        // wall_1 and wall_01 are two names for one number, so one source id.
        if (auto [it, fresh] = sourceIdAt_.emplace(*node.sourceId, std::pair{std::string(name.text), line_}); !fresh)
            fail(name, fmt::format("'{}' has the same number as '{}' (line {}): both would get source id {}", name.text,
                                   it->second.first, it->second.second, *node.sourceId));
        if (type->prefix == "wall")
            readWall(node, args, name);
        else if (type->prefix == "bbox")
            readBbox(node, args);
        else
            readOpening(node, args, std::string(type->prefix));
        nodes_.push_back(std::move(node));
    }

    std::vector<model::Node> takeNodes() { return std::move(nodes_); }

private:
    [[noreturn]] void fail(const Token& where, std::string_view what) const {
        throw Error(ErrorKind::Input, fmt::format("{}:{}: {}", path_, line_, what),
                    SourceLocation{line_, where.column, std::max(1, static_cast<int>(where.text.size()))},
                    std::string(kSpatialLmHint));
    }

    // Text that is not UTF-8 (a Latin-1 class name) would be stored and then
    // break every JSON answer about it: reject it, naming the field.
    // A layout is UTF-8 text without NUL: a NUL would cut a category short in every C string that
    // later holds it, and the smql JSON the memory exports refuses it.
    void checkText(std::string_view line) const {
        std::optional<std::size_t> bad = model::invalidUtf8At(line);
        if (std::size_t nul = line.find('\0'); nul != std::string_view::npos && (!bad || nul < *bad)) bad = nul;
        if (!bad) return;
        std::size_t equals = line.find('=');
        std::size_t open = line.find('(', equals == std::string_view::npos ? 0 : equals);
        std::string field = "the line";
        if (equals != std::string_view::npos && *bad < equals) {
            field = "name";
        } else if (open != std::string_view::npos && *bad > open) {
            std::string_view typeName = trimmed(line, equals + 1, open).text;
            std::size_t index = static_cast<std::size_t>(std::count(line.begin() + open, line.begin() + *bad, ','));
            field = fmt::format("value {}", index + 1);
            for (const EntityType& t : entityTypes())
                if (typeName == t.name && index < t.fields.size()) field = std::string(t.fields[index]);
        } else if (equals != std::string_view::npos) {
            field = "type";
        }
        if (line[*bad] == '\0')
            fail(Token{line.substr(*bad, 1), static_cast<int>(*bad) + 1},
                 fmt::format("{}: a NUL byte at column {} (names and values hold none)", field, *bad + 1));
        fail(Token{line.substr(*bad, 1), static_cast<int>(*bad) + 1},
             fmt::format("{}: byte 0x{:02X} at column {} is not UTF-8 (the file must be UTF-8 text; convert a Latin-1 "
                         "file with iconv -f latin1 -t utf-8)",
                         field, static_cast<unsigned char>(line[*bad]), *bad + 1));
    }

    std::int64_t entityNumber(const Token& name, const EntityType& type) const {
        std::string_view text = name.text;
        auto bad = [&] {
            fail(name, fmt::format("entity name '{}' does not fit its type {}: expected {}_<n>", text, type.name,
                                   type.prefix));
        };
        if (text.size() <= type.prefix.size() + 1 || !text.starts_with(type.prefix) || text[type.prefix.size()] != '_')
            bad();
        std::string_view digits = text.substr(type.prefix.size() + 1);
        std::int64_t n = 0;
        auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), n);
        if (ec != std::errc() || end != digits.data() + digits.size() ||
            !std::isdigit(static_cast<unsigned char>(digits.front())))
            bad();
        // Bboxes own the open-ended top of the id scheme; the other types share it in blocks.
        if (type.prefix != "bbox" && n >= kIdBlock)
            fail(name, fmt::format("{} numbers must be below {} (see the source id scheme)", type.prefix, kIdBlock));
        if (n > kMaxBboxNumber)
            fail(name,
                 fmt::format("{} numbers must be at most {} (see the source id scheme)", type.prefix, kMaxBboxNumber));
        return n;
    }

    static std::vector<Token> splitArguments(std::string_view line, std::size_t begin, std::size_t end) {
        std::vector<Token> args;
        if (trimmed(line, begin, end).text.empty()) return args;
        for (std::size_t start = begin;;) {
            std::size_t comma = line.find(',', start);
            if (comma == std::string_view::npos || comma >= end) {
                args.push_back(trimmed(line, start, end));
                return args;
            }
            args.push_back(trimmed(line, start, comma));
            start = comma + 1;
        }
    }

    double number(const Token& arg, std::string_view field) const {
        double value = 0;
        auto [end, ec] = std::from_chars(arg.text.data(), arg.text.data() + arg.text.size(), value);
        if (arg.text.empty() || ec != std::errc() || end != arg.text.data() + arg.text.size())
            fail(arg, fmt::format("{}: '{}' is not a number", field, arg.text));
        if (!std::isfinite(value)) fail(arg, fmt::format("{}: {} is not a finite number", field, arg.text));
        return value;
    }

    double coordinate(const Token& arg, std::string_view field) const {
        double value = number(arg, field);
        if (std::abs(value) > kMaxCoordinate)
            fail(arg, fmt::format("{}: {} is more than {} m from the origin", field, value, kMaxCoordinate));
        return value;
    }

    double size(const Token& arg, std::string_view field) const {
        double value = number(arg, field);
        if (!(value > 0) || value > kMaxSize)
            fail(arg, fmt::format("{}: {} is out of range: sizes must be in (0, {}] m", field, value, kMaxSize));
        return value;
    }

    void readWall(model::Node& node, const std::vector<Token>& args, const Token& name) {
        double ax = coordinate(args[0], "ax"), ay = coordinate(args[1], "ay"), az = coordinate(args[2], "az");
        double bx = coordinate(args[3], "bx"), by = coordinate(args[4], "by");
        coordinate(args[5], "bz");  // SpatialLM's walls are vertical: az gives the bottom
        double height = size(args[6], "height");
        double thickness = number(args[7], "thickness");
        if (thickness < 0 || thickness > kMaxSize)
            fail(args[7], fmt::format("thickness: {} is out of range: must be in [0, {}] m", thickness, kMaxSize));
        if (thickness == 0) thickness = kDefaultWallThickness;
        double length = std::hypot(bx - ax, by - ay);
        if (!(length > 0) || length > kMaxSize)
            fail(args[0], fmt::format("wall length {} is out of range: the segment must be in (0, {}] m long", length,
                                      kMaxSize));

        node.kind = model::NodeKind::Anchor;
        node.category = "wall";
        node.geometry = model::GeometryKind::Plane;
        node.box = {
            {(ax + bx) / 2, (ay + by) / 2, az + height / 2}, {length, thickness, height}, std::atan2(by - ay, bx - ax)};
        walls_[std::string(name.text)] = {node.box.yaw, thickness};
    }

    void readOpening(model::Node& node, const std::vector<Token>& args, std::string category) {
        auto wall = walls_.find(std::string(args[0].text));
        if (wall == walls_.end())
            fail(args[0], fmt::format("wall: unknown wall '{}' (walls must be defined before the doors and "
                                      "windows on them)",
                                      args[0].text));
        node.kind = model::NodeKind::Anchor;
        node.category = std::move(category);
        node.geometry = model::GeometryKind::Plane;
        node.box = {
            {coordinate(args[1], "position_x"), coordinate(args[2], "position_y"), coordinate(args[3], "position_z")},
            {size(args[4], "width"), wall->second.thickness, size(args[5], "height")},
            wall->second.yaw};
    }

    void readBbox(model::Node& node, const std::vector<Token>& args) {
        if (args[0].text.empty()) fail(args[0], "class: empty class name");
        node.kind = model::NodeKind::Object;
        node.category = model::categoryName(args[0].text);
        node.geometry = model::GeometryKind::Box;
        node.box.center = {coordinate(args[1], "position_x"), coordinate(args[2], "position_y"),
                           coordinate(args[3], "position_z")};
        double angle = number(args[4], "angle_z");
        if (std::string problem = detail::angleProblem(angle); !problem.empty()) fail(args[4], "angle_z: " + problem);
        node.box.yaw = detail::normaliseYaw(angle);
        node.box.size = {size(args[5], "scale_x"), size(args[6], "scale_y"), size(args[7], "scale_z")};
    }

    const std::string& path_;
    int line_ = 0;
    std::map<std::string, int> definedAt_;
    std::map<std::int64_t, std::pair<std::string, int>> sourceIdAt_;  // source id -> name, line
    std::map<std::string, WallInfo> walls_;
    std::vector<model::Node> nodes_;
};

}  // namespace

model::SceneData readSpatialLm(const std::string& path, const std::string& sceneName) {
    std::string text = detail::readTextFile(path, std::string(kSpatialLmHint));
    LayoutParser parser(path);
    int lineNumber = 0;
    // Editors on some systems start UTF-8 files with a byte order mark.
    std::size_t bom = std::string_view(text).starts_with("\xEF\xBB\xBF") ? 3 : 0;
    for (std::size_t start = bom; start <= text.size();) {
        std::size_t end = text.find('\n', start);
        if (end == std::string::npos) end = text.size();
        std::string_view line(text.data() + start, end - start);
        if (line.ends_with('\r')) line.remove_suffix(1);
        parser.parseLine(++lineNumber, line);
        start = end + 1;
    }

    model::SceneData scene;
    scene.nodes = parser.takeNodes();
    if (scene.nodes.empty())
        throw Error(ErrorKind::Input, path + ": no walls, doors, windows or bboxes in the file", std::nullopt,
                    std::string(kSpatialLmHint));
    std::string name = sceneName.empty() ? std::filesystem::path(path).stem().string() : sceneName;
    detail::finishScene(scene, name, "spatiallm:" + path);
    return scene;
}

}  // namespace smql::import
