#include "engine/ask/model_translator.hpp"

#include <regex>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "engine/ask/http_post.hpp"
#include "model/error.hpp"

namespace smql::ask {

namespace {

constexpr double kTimeoutSeconds = 30;

std::string joinedNames(const std::vector<std::string>& names) {
    std::string out;
    for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
    return out.empty() ? "(none)" : out;
}

// What the model is told once per question: how to answer, SMQL in brief, the scene's words.
std::string systemPrompt(const Question& q) {
    return fmt::format(
        "You translate a person's question about one indoor scene into one SMQL statement that answers it. "
        "Reply with the statement only: no explanation, no code fence.\n\n{}\n\n"
        "The scene '{}' holds these categories (use them as written): {}.\n"
        "Of these, walls, doors and windows: {}.\n"
        "Attributes its nodes carry besides the built-in ones: {}.",
        q.grammar, q.scene, joinedNames(q.categories), joinedNames(q.planeCategories), joinedNames(q.attributes));
}

// The statement in a model's reply: a code fence, a leading "SMQL:" and a trailing ';' taken off.
std::string statementIn(std::string content) {
    static const std::regex fence(R"(```[A-Za-z]*\s*([\s\S]*?)```)");
    std::smatch m;
    if (std::regex_search(content, m, fence)) content = m.str(1);
    static const std::regex label(R"(^\s*(?:SMQL|Statement|Answer)\s*:\s*)", std::regex::icase);
    content = std::regex_replace(content, label, "");
    while (!content.empty() && std::isspace(static_cast<unsigned char>(content.back()))) content.pop_back();
    while (!content.empty() && content.back() == ';') content.pop_back();
    std::size_t start = content.find_first_not_of(" \t\r\n");
    return start == std::string::npos ? std::string() : content.substr(start);
}

class ModelTranslator final : public Translator {
public:
    ModelTranslator(std::string origin, std::string path, std::string model, std::string url)
        : origin_(std::move(origin)), path_(std::move(path)), model_(std::move(model)), url_(std::move(url)) {}

    Translation translate(const Question& q) const override {
        nlohmann::json messages = nlohmann::json::array(
            {{{"role", "system"}, {"content", systemPrompt(q)}}, {{"role", "user"}, {"content", q.text}}});
        return ask(q, messages, "");
    }

    std::optional<Translation> repair(const Question& q, const Translation& failed,
                                      const std::string& error) const override {
        nlohmann::json messages = nlohmann::json::array(
            {{{"role", "system"}, {"content", systemPrompt(q)}},
             {{"role", "user"}, {"content", q.text}},
             {{"role", "assistant"}, {"content", failed.smql}},
             {{"role", "user"},
              {"content", fmt::format("That statement failed: {}\nReply with a corrected statement only.", error)}}});
        return ask(q, messages, fmt::format("its first statement ({}) failed: {}", failed.smql, error));
    }

    std::string name() const override { return url_; }

private:
    Translation ask(const Question& q, const nlohmann::json& messages, const std::string& repaired) const {
        nlohmann::json request{{"model", model_}, {"messages", messages}, {"temperature", 0}, {"stream", false}};
        HttpReply reply = httpPost(origin_, path_, request.dump(), kTimeoutSeconds);
        if (!reply.body) throw Unavailable(reply.error);
        std::string content;
        try {
            auto json = nlohmann::json::parse(*reply.body);
            content = json.at("choices").at(0).at("message").at("content").get<std::string>();
        } catch (const std::exception&) {
            throw Unavailable("its reply is not a chat completion");
        }
        Translation out;
        out.kind = QuestionKind::Statement;
        out.smql = statementIn(content);
        if (out.smql.empty()) throw Unavailable("its reply holds no statement");
        out.subject = "thing";
        out.subjectPlural = "things";
        out.notes.push_back(repaired.empty()
                                ? fmt::format("translated by the model at {}", url_)
                                : fmt::format("translated by the model at {}, repaired: {}", url_, repaired));
        (void)q;
        return out;
    }

    std::string origin_, path_, model_, url_;
};

}  // namespace

std::shared_ptr<const Translator> modelTranslator(const std::string& url) {
    static const std::regex form(R"(^(http://[^/#?]+)(/[^#?]*)?(?:#(.+))?$)");
    std::smatch m;
    if (!std::regex_match(url, m, form))
        throw Error(ErrorKind::Binding, fmt::format("cannot read the translator's URL '{}'", url), std::nullopt,
                    "SET translator = 'http://127.0.0.1:8080/v1' (an OpenAI-compatible endpoint; '#model' names "
                    "the model), or 'built-in'");
    std::string path = m.str(2);
    while (!path.empty() && path.back() == '/') path.pop_back();
    std::string model = m[3].matched ? m.str(3) : "smql";
    return std::make_shared<ModelTranslator>(m.str(1), path + "/chat/completions", model, url);
}

}  // namespace smql::ask
