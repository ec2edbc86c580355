// Result sets as JSON when the stored text is not UTF-8 (a database written
// before imports checked their text).
#include <catch2/catch.hpp>

#include "engine/format.hpp"

using namespace smql;

TEST_CASE("JSON output replaces bytes that are not UTF-8 instead of failing", "[format][utf8]") {
    ResultSet result;
    result.columns = {Column{"category", ValueType::Text}};
    result.rows = {{Value{std::string("caf\xE9")}}, {Value{std::string("sofa")}}};
    result.message = "note \xFF";
    std::string text;
    REQUIRE_NOTHROW(text = jsonText(resultJson(result)));
    CHECK(text ==
          "{\"columns\":[\"category\"],\"rows\":[{\"category\":\"caf\xEF\xBF\xBD\"},{\"category\":\"sofa\"}],"
          "\"message\":\"note \xEF\xBF\xBD\"}");
    nlohmann::json error = {{"error", {{"message", "bad \xE9"}}}};
    CHECK(jsonText(error) == "{\"error\":{\"message\":\"bad \xEF\xBF\xBD\"}}");
}
