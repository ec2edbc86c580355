#include <string>

#include "engine/engine.hpp"
#include "engine/format.hpp"
#include "model/base64.hpp"
#include "view/assets.hpp"
#include "view/scene_json.hpp"
#include "view/view.hpp"

namespace smql::view {

std::string standalonePage(Engine& engine, const std::string& scene) {
    const std::string data = jsonText(sceneJson(engine.readScene(scene)));
    auto text = [](std::string_view path) { return std::string(findAsset(path)->bytes); };
    // Modules come from data: URLs mapped by an import map, so the file needs no server; the
    // scene is a JSON script element the page reads instead of asking /api/scene.
    auto dataUrl = [](const std::string& source) { return "data:text/javascript;base64," + model::toBase64(source); };
    nlohmann::ordered_json imports = {
        {"three", dataUrl(text("/assets/three.module.min.js"))},
        {"three/addons/controls/OrbitControls.js", dataUrl(text("/assets/addons/controls/OrbitControls.js"))}};
    std::string page = text("/");
    // The served page's import map, style sheet link and script element, each replaced by what it
    // points to.
    auto replaceElement = [&page](std::string_view start, std::string_view end, const std::string& with) {
        auto from = page.find(start);
        auto to = from == std::string::npos ? from : page.find(end, from);
        if (to != std::string::npos) page.replace(from, to + end.size() - from, with);
    };
    // "</" cannot end a script element early inside JSON: written as "<\/".
    std::string safeData = data;
    for (auto at = safeData.find("</"); at != std::string::npos; at = safeData.find("</", at + 3))
        safeData.replace(at, 2, "<\\/");
    replaceElement(
        "<script type=\"importmap\">", "</script>",
        "<script type=\"importmap\">" + jsonText(nlohmann::ordered_json{{"imports", imports}}) + "</script>");
    replaceElement("<link rel=\"stylesheet\"", ">", "<style>" + text("/assets/view.css") + "</style>");
    replaceElement("<script type=\"module\"", "</script>",
                   "<script type=\"application/json\" id=\"smql-scene\">" + safeData +
                       "</script>\n<script type=\"module\">" + text("/assets/view.js") + "</script>");
    return page;
}

}  // namespace smql::view
