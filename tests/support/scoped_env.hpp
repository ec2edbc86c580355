// An environment variable set for one scope, as it was after (unset when it was unset): the tests that point
// smql at another module folder, COLMAP, or temporary folder.
#pragma once

#include <cstdlib>
#include <optional>
#include <string>
#include <utility>

namespace smql::testing {

class ScopedEnv {
public:
    ScopedEnv(std::string name, const std::string& value) : name_(std::move(name)) {
        if (const char* was = std::getenv(name_.c_str())) before_ = was;
        setenv(name_.c_str(), value.c_str(), 1);
    }
    ~ScopedEnv() {
        if (before_)
            setenv(name_.c_str(), before_->c_str(), 1);
        else
            unsetenv(name_.c_str());
    }
    ScopedEnv(const ScopedEnv&) = delete;
    ScopedEnv& operator=(const ScopedEnv&) = delete;

private:
    std::string name_;
    std::optional<std::string> before_;
};

}  // namespace smql::testing
