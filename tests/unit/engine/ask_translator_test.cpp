// ASK through a language model's endpoint: `SET translator = 'http://127.0.0.1:PORT/v1'`. The test
// serves an OpenAI-compatible chat completions endpoint on 127.0.0.1 (cpp-httplib) that replays
// recorded replies, good and bad, and checks what the engine sent, the repair after a statement that
// does not bind, and the built-in reader answering when the endpoint fails or is absent.
#include <chrono>
#include <deque>
#include <mutex>
#include <thread>

#include <fmt/format.h>
#include <httplib.h>
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "engine_support.hpp"
#include "ingest/import/importers.hpp"

using namespace smql;
using smql::testing::run;
using smql::testing::TempDir;

namespace {

// The endpoint: each request takes the next recorded reply (a status and the model's text).
class ReplayedEndpoint {
public:
    ReplayedEndpoint() {
        server_.Post("/v1/chat/completions", [this](const httplib::Request& req, httplib::Response& res) {
            std::lock_guard lock(mutex_);
            requests_.push_back(nlohmann::json::parse(req.body));
            if (replies_.empty()) {
                res.status = 500;
                return;
            }
            auto [status, content] = replies_.front();
            replies_.pop_front();
            res.status = status;
            nlohmann::json body = status == 200 && content != "not json"
                                      ? nlohmann::json{{"id", "chatcmpl-1"},
                                                       {"object", "chat.completion"},
                                                       {"choices",
                                                        {{{"index", 0},
                                                          {"message", {{"role", "assistant"}, {"content", content}}},
                                                          {"finish_reason", "stop"}}}}}
                                      : nlohmann::json{{"error", content}};
            res.set_content(body.dump(), "application/json");
        });
        port_ = server_.bind_to_any_port("127.0.0.1");
        thread_ = std::thread([this] { server_.listen_after_bind(); });
        while (!server_.is_running()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    ~ReplayedEndpoint() {
        server_.stop();
        thread_.join();
    }
    std::string url() const { return fmt::format("http://127.0.0.1:{}/v1", port_); }
    void reply(std::vector<std::pair<int, std::string>> replies) {
        std::lock_guard lock(mutex_);
        replies_.assign(replies.begin(), replies.end());
        requests_.clear();
    }
    std::vector<nlohmann::json> requests() {
        std::lock_guard lock(mutex_);
        return requests_;
    }

private:
    httplib::Server server_;
    int port_ = 0;
    std::thread thread_;
    std::mutex mutex_;
    std::deque<std::pair<int, std::string>> replies_;
    std::vector<nlohmann::json> requests_;
};

std::string smqlLine(const ResultSet& rs) { return rs.message.substr(0, rs.message.find('\n')); }

}  // namespace

TEST_CASE("ASK through a model's endpoint: its SMQL, a repair, and the built-in reader when it fails", "[ask]") {
    TempDir dir;
    auto engine = Engine::open(dir.path.string());
    engine->importScene(import::readReplica(testing::replicaRoom0(), "replica-room0"));
    ReplayedEndpoint endpoint;
    run(*engine, fmt::format("SET translator = '{}'", endpoint.url()));
    const auto onSofa = run(*engine, "FIND object WHERE on(sofa)");

    SECTION("its statement runs, and it was sent the question, the scene's words and SMQL in brief") {
        endpoint.reply({{200, "FIND object WHERE on(sofa)"}});
        auto rs = run(*engine, "ASK 'what sits on the couch?'");
        CHECK(smqlLine(rs) == "SMQL: FIND object WHERE on(sofa)");
        CHECK(rs.rows.size() == onSofa.rows.size());
        CHECK(rs.message.find("Note: translated by the model at " + endpoint.url()) != std::string::npos);
        auto sent = endpoint.requests();
        REQUIRE(sent.size() == 1);
        const auto& messages = sent[0]["messages"];
        REQUIRE(messages.size() == 2);
        const std::string system = messages[0]["content"];
        CHECK(system.find("cushion") != std::string::npos);                          // the scene's categories
        CHECK(system.find("near(sofa) or near(sofa, 1.5 m)") != std::string::npos);  // the predicate table
        CHECK(system.find("volume") != std::string::npos);                           // the attribute table
        CHECK(messages[1]["content"] == "what sits on the couch?");
        CHECK(sent[0]["model"] == "smql");
    }

    SECTION("a statement in a code fence, with a label and a semicolon, is read") {
        endpoint.reply({{200, "SMQL: ```sql\nCOUNT cushion WHERE on(sofa);\n```"}});
        auto rs = run(*engine, "ASK 'how many cushions are on the sofa?'");
        CHECK(smqlLine(rs) == "SMQL: COUNT cushion WHERE on(sofa)");
        CHECK(rs.rows == run(*engine, "COUNT cushion WHERE on(sofa)").rows);
    }

    SECTION("a statement that does not bind goes back once with its error, and the repair runs") {
        endpoint.reply({{200, "FIND object WHERE onn(sofa)"}, {200, "FIND object WHERE on(sofa)"}});
        auto rs = run(*engine, "ASK 'what is on the sofa?'");
        CHECK(smqlLine(rs) == "SMQL: FIND object WHERE on(sofa)");
        CHECK(rs.rows.size() == onSofa.rows.size());
        CHECK(rs.message.find("repaired: its first statement (FIND object WHERE onn(sofa)) failed") !=
              std::string::npos);
        auto sent = endpoint.requests();
        REQUIRE(sent.size() == 2);
        const auto& messages = sent[1]["messages"];
        REQUIRE(messages.size() == 4);
        CHECK(messages[2]["content"] == "FIND object WHERE onn(sofa)");
        const std::string error = messages[3]["content"];
        CHECK(error.find("That statement failed") != std::string::npos);
        CHECK(error.find("onn") != std::string::npos);
    }

    SECTION("a write, then a statement that fails again: the built-in reader answers, with a note") {
        endpoint.reply({{200, "USE SCENE 'replica-room0'"}, {200, "FIND object WHERE (("}});
        auto rs = run(*engine, "ASK 'what is on the sofa?'");
        CHECK(smqlLine(rs) == "SMQL: FIND object WHERE on(sofa)");
        CHECK(rs.rows.size() == onSofa.rows.size());
        CHECK(rs.message.find("a question must translate to one statement that reads") != std::string::npos);
        CHECK(rs.message.find("its repair (FIND object WHERE (() failed too") != std::string::npos);
        CHECK(rs.message.find("the built-in reader answered") != std::string::npos);
        CHECK(endpoint.requests().size() == 2);
    }

    SECTION("an endpoint that fails, or replies with no completion: the built-in reader answers") {
        endpoint.reply({{500, "overloaded"}});
        auto failed = run(*engine, "ASK 'how many cushions are on the sofa?'");
        CHECK(smqlLine(failed) == "SMQL: COUNT cushion WHERE on(sofa)");
        CHECK(failed.message.find("failed (HTTP status 500") != std::string::npos);
        CHECK(failed.message.find("the built-in reader answered") != std::string::npos);

        endpoint.reply({{200, "not json"}});
        auto garbled = run(*engine, "ASK 'how many cushions are on the sofa?'");
        CHECK(garbled.message.find("its reply is not a chat completion") != std::string::npos);
        CHECK(garbled.rows == failed.rows);

        endpoint.reply({{200, "  "}});
        auto empty = run(*engine, "ASK 'how many cushions are on the sofa?'");
        CHECK(empty.message.find("its reply holds no statement") != std::string::npos);
    }

    SECTION("an endpoint that is absent: the built-in reader answers; 'built-in' turns the model off") {
        std::string closed;
        {
            ReplayedEndpoint gone;
            closed = gone.url();
        }
        run(*engine, fmt::format("SET translator = '{}'", closed));
        auto rs = run(*engine, "ASK 'what is on the sofa?'");
        CHECK(smqlLine(rs) == "SMQL: FIND object WHERE on(sofa)");
        CHECK(rs.message.find("the translator at " + closed + " failed") != std::string::npos);
        run(*engine, "SET translator = 'built-in'");
        auto plain = run(*engine, "ASK 'what is on the sofa?'");
        CHECK(plain.message.find("Note:") == std::string::npos);
        CHECK(endpoint.requests().empty());
    }

    SECTION("a URL it cannot read is an error") {
        CHECK_THROWS_WITH(run(*engine, "SET translator = 'ftp://127.0.0.1/v1'"),
                          Catch::Contains("cannot read the translator's URL"));
        CHECK_THROWS_WITH(run(*engine, "SET translator = 5"), Catch::Contains("translator takes a URL"));
    }
}
