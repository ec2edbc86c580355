#include "view/view.hpp"

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <random>
#include <thread>
#include <vector>

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

// The API: every answer is JSON; a user's mistake is a 400 with the engine's error. Each request runs
// on an engine of its own (read-only, sharing the process's LMDB environment: opening one costs
// microseconds), so a request's USE SCENE or SET never reaches another's.
class Api {
public:
    explicit Api(const ViewOptions& options)
        : database_(options.database), limit_(options.statementMilliseconds), start_(options.scene) {}

    void scenes(httplib::Response& response) {
        answer(response, "", [&] {
            auto engine = Engine::open(database_, /*readOnly=*/true);
            ResultSet shown = engine->execute("SHOW SCENES").back();
            auto names = nlohmann::ordered_json::array();
            for (const auto& row : shown.rows) names.push_back(std::get<std::string>(row[0]));
            return nlohmann::ordered_json{{"scenes", names},
                                          {"current", start_.empty() ? engine->currentScene() : start_}};
        });
    }

    void scene(const httplib::Request& request, httplib::Response& response) {
        answer(response, "", [&] {
            return sceneJson(Engine::open(database_, /*readOnly=*/true)->readScene(request.get_param_value("name")));
        });
    }

    void query(const httplib::Request& request, httplib::Response& response) {
        const std::string statement = request.get_param_value("q");
        const std::string scene = request.has_param("scene") ? request.get_param_value("scene") : start_;
        answer(response, statement, [&] {
            auto engine = Engine::open(database_, /*readOnly=*/true);
            if (!scene.empty()) engine->execute("USE SCENE " + model::quoted(scene));
            Deadline deadline(*engine, limit_);
            auto results = engine->execute(statement);
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

    std::string database_;
    std::chrono::milliseconds limit_;
    std::string start_;
};

// A fresh random token for the API: 128 bits from the system's random device, as hex.
std::string randomToken() {
    std::random_device device;
    std::string out;
    for (int i = 0; i < 4; ++i) out += fmt::format("{:08x}", device());
    return out;
}

// One thread a connection, up to kMaxConnections at once (the next wait their turn): a slow client
// holds its own thread, never the one a real request needs; its reads time out after
// kReadTimeout, an idle kept-alive connection after kIdleTimeout.
constexpr std::size_t kMaxConnections = 1024;
constexpr std::chrono::seconds kReadTimeout{5}, kIdleTimeout{5};

class ConnectionThreads : public httplib::TaskQueue {
public:
    void enqueue(std::function<void()> job) override {
        std::lock_guard lock(mutex_);
        waiting_.push_back(std::move(job));
        // A thread for the connection unless one waits idle, up to the cap.
        if (idle_ == 0 && threads_.size() < kMaxConnections) threads_.emplace_back([this] { work(); });
        ready_.notify_one();
    }

    void shutdown() override {
        {
            std::lock_guard lock(mutex_);
            stopping_ = true;
        }
        ready_.notify_all();
        for (auto& t : threads_) t.join();
    }

private:
    void work() {
        std::unique_lock lock(mutex_);
        for (;;) {
            ++idle_;
            ready_.wait(lock, [this] { return stopping_ || !waiting_.empty(); });
            --idle_;
            if (stopping_) return;
            auto job = std::move(waiting_.front());
            waiting_.pop_front();
            lock.unlock();
            job();
            lock.lock();
        }
    }

    std::mutex mutex_;
    std::condition_variable ready_;
    std::deque<std::function<void()>> waiting_;
    std::vector<std::thread> threads_;
    std::size_t idle_ = 0;
    bool stopping_ = false;
};

}  // namespace

void serve(const ViewOptions& options, const std::function<void(const std::string& url)>& listening) {
    // Read-only: nothing the page sends can change the database. Opened here so that a database that
    // is not there is an error before the server listens, and kept so that the requests' engines share
    // its environment.
    auto engine = Engine::open(options.database, /*readOnly=*/true);
    if (!options.scene.empty()) engine->execute("USE SCENE " + model::quoted(options.scene));
    Api api(options);
    const std::string token = options.token.empty() ? randomToken() : options.token;

    httplib::Server server;
    server.new_task_queue = [] { return new ConnectionThreads; };
    server.set_read_timeout(kReadTimeout);
    server.set_write_timeout(kReadTimeout);
    server.set_keep_alive_timeout(kIdleTimeout.count());
    int port = options.port;
    // Only this machine's names for this server (no DNS rebinding: a page of another site that
    // resolves its own name to 127.0.0.1 sends its own Host), and every API call with the token the
    // printed address carries (no other page on this machine can use the API: it does not know it).
    server.set_pre_routing_handler([&](const httplib::Request& request, httplib::Response& response) {
        const std::string host = request.get_header_value("Host");
        const bool ours = host == fmt::format("127.0.0.1:{}", port) || host == fmt::format("localhost:{}", port) ||
                          host == fmt::format("[::1]:{}", port) || host == fmt::format("{}:{}", options.host, port);
        const bool api = request.path.rfind("/api/", 0) == 0;
        const std::string given = request.has_header("X-Smql-Token") ? request.get_header_value("X-Smql-Token")
                                                                     : request.get_param_value("token");
        if (ours && (!api || given == token)) return httplib::Server::HandlerResponse::Unhandled;
        response.status = 403;
        response.set_content(ours ? "the API needs the token of the address smql view printed"
                                  : "this server answers to 127.0.0.1 and localhost only",
                             "text/plain");
        return httplib::Server::HandlerResponse::Handled;
    });
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

    if (port == 0) {
        port = server.bind_to_any_port(options.host);
        if (port < 0) port = 0;
    } else if (!server.bind_to_port(options.host, port)) {
        port = 0;
    }
    if (port == 0)
        throw Error(ErrorKind::Usage, fmt::format("cannot listen on {}:{}", options.host, options.port), std::nullopt,
                    "another program may use the port: --port N picks another, --port 0 any free one");
    listening(fmt::format("http://{}:{}/?token={}", options.host, port, token));
    server.listen_after_bind();
}

}  // namespace smql::view
