#include "view/view.hpp"

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>

#include <fmt/format.h>
#include <httplib.h>

#include "engine/engine.hpp"
#include "engine/format.hpp"
#include "model/error.hpp"
#include "model/names.hpp"
#include "view/assets.hpp"
#include "view/scene_json.hpp"

namespace smql::view {

namespace {

// Interrupts the engine's statement when it runs past its time; the statement then fails with
// Error(Interrupted) and the page shows why.
class Deadline {
public:
    Deadline(Engine& engine, std::chrono::milliseconds limit)
        : watcher_([this, &engine, limit] {
              std::unique_lock lock(mutex_);
              if (!done_.wait_for(lock, limit, [this] { return finished_; })) engine.interrupt();
          }) {}
    ~Deadline() {
        {
            std::lock_guard lock(mutex_);
            finished_ = true;
        }
        done_.notify_one();
        watcher_.join();
    }
    Deadline(const Deadline&) = delete;
    Deadline& operator=(const Deadline&) = delete;

private:
    std::mutex mutex_;
    std::condition_variable done_;
    bool finished_ = false;
    std::thread watcher_;  // last: it starts once the members it reads exist
};

nlohmann::ordered_json errorJson(const Error& e, const std::string& statement) {
    nlohmann::ordered_json out = {
        {"kind", toString(e.kind())}, {"message", e.message()}, {"hint", e.hint()}, {"text", e.render(statement)}};
    if (e.where()) out["line"] = e.where()->line, out["column"] = e.where()->column;
    return {{"error", out}};
}

void sendJson(httplib::Response& response, const nlohmann::ordered_json& body, int status = 200) {
    response.status = status;
    response.set_content(jsonText(body), "application/json; charset=utf-8");
}

// The API: every answer is JSON; a user's mistake is a 400 with the engine's error.
class Api {
public:
    Api(std::unique_ptr<Engine> engine, const ViewOptions& options)
        : engine_(std::move(engine)), limit_(options.statementMilliseconds), start_(options.scene) {}

    void scenes(httplib::Response& response) {
        std::lock_guard lock(mutex_);
        ResultSet shown = engine_->execute("SHOW SCENES").back();
        auto names = nlohmann::ordered_json::array();
        for (const auto& row : shown.rows) names.push_back(std::get<std::string>(row[0]));
        std::string current = start_.empty() ? engine_->currentScene() : start_;
        sendJson(response, {{"scenes", names}, {"current", current}});
    }

    void scene(const httplib::Request& request, httplib::Response& response) {
        std::lock_guard lock(mutex_);
        answer(response, "", [&] { return sceneJson(engine_->readScene(request.get_param_value("name"))); });
    }

    void query(const httplib::Request& request, httplib::Response& response) {
        const std::string statement = request.get_param_value("q");
        const std::string scene = request.get_param_value("scene");
        std::lock_guard lock(mutex_);
        answer(response, statement, [&] {
            if (!scene.empty()) engine_->execute("USE SCENE " + model::quoted(scene));
            Deadline deadline(*engine_, limit_);
            auto results = engine_->execute(statement);
            if (results.empty())
                throw Error(ErrorKind::Usage, "no statement to run", std::nullopt,
                            "FIND cushion WHERE on(sofa), or ASK 'where is the sofa?'");
            return answerJson(results.back());
        });
    }

private:
    template <class Body>
    void answer(httplib::Response& response, const std::string& statement, Body&& body) {
        try {
            sendJson(response, body());
        } catch (const Error& e) {
            sendJson(response, errorJson(e, statement), 400);
        }
    }

    std::mutex mutex_;  // one session: a request's USE SCENE and its statement run together
    std::unique_ptr<Engine> engine_;
    std::chrono::milliseconds limit_;
    std::string start_;
};

}  // namespace

void serve(const ViewOptions& options, const std::function<void(const std::string& url)>& listening) {
    // Read-only: nothing the page sends can change the database.
    auto engine = Engine::open(options.database, /*readOnly=*/true);
    if (!options.scene.empty()) engine->execute("USE SCENE " + model::quoted(options.scene));
    Api api(std::move(engine), options);

    httplib::Server server;
    server.Get("/api/scenes", [&](const httplib::Request&, httplib::Response& r) { api.scenes(r); });
    server.Get("/api/scene", [&](const httplib::Request& q, httplib::Response& r) { api.scene(q, r); });
    server.Get("/api/query", [&](const httplib::Request& q, httplib::Response& r) { api.query(q, r); });
    // Everything else is one of the built-in files, or not there: no path reaches the file system.
    server.Get(R"(/.*)", [](const httplib::Request& request, httplib::Response& response) {
        const Asset* asset = findAsset(request.path == "/index.html" ? "/" : request.path);
        if (!asset) {
            response.status = 404;
            response.set_content("not found", "text/plain");
            return;
        }
        response.set_header("Cache-Control", "no-cache");
        response.set_content(std::string(asset->bytes), std::string(asset->mediaType) + "; charset=utf-8");
    });

    int port = options.port;
    if (port == 0) {
        port = server.bind_to_any_port(options.host);
        if (port < 0) port = 0;
    } else if (!server.bind_to_port(options.host, port)) {
        port = 0;
    }
    if (port == 0)
        throw Error(ErrorKind::Usage, fmt::format("cannot listen on {}:{}", options.host, options.port), std::nullopt,
                    "another program may use the port: --port N picks another, --port 0 any free one");
    listening(fmt::format("http://{}:{}/", options.host, port));
    server.listen_after_bind();
}

}  // namespace smql::view
