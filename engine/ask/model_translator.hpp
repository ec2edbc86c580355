// A translator that asks a language model: the question, the scene's vocabulary and a summary of
// SMQL's grammar go to an OpenAI-compatible chat completions endpoint the user runs (llama.cpp's
// server, Ollama, vLLM: `SET translator = 'http://127.0.0.1:8080/v1'`), and the statement it
// answers is the translation. The binder parses and binds it before it runs; an error goes back to
// the model once for a repair (`repair`), and where the endpoint is absent or fails, or its SMQL
// fails twice, the built-in reader answers, with a note saying so (engine/binder/bind_ask.cpp).
#pragma once

#include <memory>
#include <string>

#include "engine/ask/translator.hpp"

namespace smql::ask {

// `url` is the endpoint's base (`http://127.0.0.1:8080/v1`, the requests go to its
// /chat/completions), with the model's name after a '#' where the server needs one
// (`http://127.0.0.1:11434/v1#qwen2.5`). Throws smql::Error (Binding) for a URL it cannot read.
std::shared_ptr<const Translator> modelTranslator(const std::string& url);

}  // namespace smql::ask
