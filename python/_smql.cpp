// _smql: smql.h as a Python extension module. It holds no logic of its own: each method is one C
// API call (with the GIL released around the calls that run statements or ingest), and failures
// raise the PEP 249 exception classes of smql/errors.py carrying the engine's message, line,
// column and hint. smql/__init__.py builds the PEP 249 interface on it.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <optional>
#include <string>
#include <vector>

#include "smql.h"

namespace py = pybind11;

namespace {

// The exception class of each status (smql/errors.py), as Python's sqlite3 maps SQLite's codes.
const char* exceptionName(smql_status status) {
    switch (status) {
        case SMQL_ERROR_SYNTAX:
        case SMQL_ERROR_BINDING:
        case SMQL_ERROR_USAGE:
            return "ProgrammingError";
        case SMQL_ERROR_INPUT:
            return "DataError";
        case SMQL_ERROR_MISUSE:
            return "InterfaceError";
        case SMQL_ERROR_INTERNAL:
            return "InternalError";
        default:  // storage, limit, interrupted
            return "OperationalError";
    }
}

// The rendered text's "hint: ..." line, which smql_errmsg ends with when there is one.
std::string hintOf(const std::string& text) {
    auto at = text.rfind("hint: ");
    if (at == std::string::npos) return {};
    auto end = text.find('\n', at);
    return text.substr(at + 6, end == std::string::npos ? std::string::npos : end - at - 6);
}

[[noreturn]] void raise(smql_status status, const std::string& message, int line, int column) {
    py::object errors = py::module_::import("smql.errors");
    py::object error = errors.attr(exceptionName(status))(message);
    error.attr("status") = static_cast<int>(status);
    error.attr("status_name") = smql_status_string(status);
    error.attr("line") = line;
    error.attr("column") = column;
    error.attr("hint") = hintOf(message);
    PyErr_SetObject(error.get_type().ptr(), error.ptr());
    throw py::error_already_set();
}

void check(smql_db* db, smql_status status) {
    if (status != SMQL_OK && status != SMQL_ROW && status != SMQL_DONE)
        raise(status, smql_errmsg(db), smql_error_line(db), smql_error_column(db));
}

py::object boxTuple(const smql_box& b) {
    return py::make_tuple(b.center[0], b.center[1], b.center[2], b.size[0], b.size[1], b.size[2], b.yaw);
}

class Statement;

class Database {
public:
    Database(const std::string& path, bool readOnly) {
        smql_status status = smql_open(path.c_str(), readOnly ? SMQL_OPEN_READONLY : 0, &db_);
        if (status != SMQL_OK) {
            std::string message = db_ ? smql_errmsg(db_) : "out of memory";
            smql_close(db_);
            db_ = nullptr;
            raise(status, message, 0, 0);
        }
    }
    ~Database() { close(); }
    Database(const Database&) = delete;
    Database& operator=(const Database&) = delete;

    void close() {
        smql_close(db_);
        db_ = nullptr;
    }
    bool isOpen() const { return db_ != nullptr; }
    smql_db* handle() const {
        if (!db_) raise(SMQL_ERROR_MISUSE, "the connection is closed", 0, 0);
        return db_;
    }

    // Every ';'-separated statement, in order (executescript); the messages of each.
    std::vector<std::string> executeScript(const std::string& text) {
        smql_result* result = nullptr;
        smql_status status;
        {
            py::gil_scoped_release release;
            status = smql_execute(handle(), text.c_str(), &result);
        }
        check(db_, status);
        std::vector<std::string> messages;
        for (size_t i = 0; i < smql_statement_count(result); ++i)
            messages.emplace_back(smql_statement_message(result, i));
        smql_result_free(result);
        return messages;
    }

    void exportScene(const std::string& format, std::optional<std::string> scene, const std::string& path) {
        smql_status status;
        {
            py::gil_scoped_release release;
            status = smql_export(handle(), format.c_str(), scene ? scene->c_str() : nullptr, path.c_str());
        }
        check(db_, status);
    }

    void exportPoints(std::optional<std::string> scene, const std::string& path) {
        smql_status status;
        {
            py::gil_scoped_release release;
            status = smql_export_points(handle(), scene ? scene->c_str() : nullptr, path.c_str());
        }
        check(db_, status);
    }

    void interrupt() {
        if (db_) smql_interrupt(db_);
    }

    // ASK's translator: an endpoint's URL, or "built-in" (smql_translator, smql_set_translator).
    std::string translator() const {
        const char* name = smql_translator(handle());
        return name ? name : "";
    }
    void setTranslator(std::optional<std::string> url) {
        check(db_, smql_set_translator(handle(), url ? url->c_str() : nullptr));
    }

    void importFile(const std::string& format, const std::string& path, std::optional<std::string> scene, bool update) {
        smql_status status;
        {
            py::gil_scoped_release release;
            const char* name = scene ? scene->c_str() : nullptr;
            status = update ? smql_update_file(handle(), format.c_str(), path.c_str(), name)
                            : smql_import_file(handle(), format.c_str(), path.c_str(), name);
        }
        check(db_, status);
    }

    // progress(kind, stage, done, total, seconds, text) -> truthy to stop. An exception it raises
    // stops the ingest and is raised again here, and so does Ctrl-C (KeyboardInterrupt): Python's
    // signal handlers run at each event, with or without `progress`, as a long C call should let them.
    void ingest(const std::string& capture, const std::string& options, py::object progress) {
        struct Context {
            py::object progress;
            std::optional<py::error_already_set> raised;
        } context{std::move(progress), std::nullopt};
        auto callback = [](void* user, const smql_progress* p) -> int {
            auto* c = static_cast<Context*>(user);
            py::gil_scoped_acquire acquire;
            try {
                if (PyErr_CheckSignals() != 0) throw py::error_already_set();
                if (c->progress.is_none()) return 0;
                return py::bool_(
                           c->progress(static_cast<int>(p->kind), p->stage, p->done, p->total, p->seconds, p->text))
                           ? 1
                           : 0;
            } catch (py::error_already_set& e) {
                c->raised = std::move(e);
                return 1;
            }
        };
        smql_status status;
        {
            py::gil_scoped_release release;
            status = smql_ingest(handle(), capture.c_str(), options.empty() ? nullptr : options.c_str(), +callback,
                                 &context);
        }
        if (context.raised) throw std::move(*context.raised);
        check(db_, status);
    }

    // A whole result of smql_evaluate or smql_check_ingest: (columns, rows).
    py::tuple evaluate(std::optional<std::string> suite, std::optional<std::string> scene) {
        smql_result* result = nullptr;
        smql_status status;
        {
            py::gil_scoped_release release;
            status =
                smql_evaluate(handle(), suite ? suite->c_str() : nullptr, scene ? scene->c_str() : nullptr, &result);
        }
        check(db_, status);
        return table(result);
    }
    py::tuple checkIngest(std::optional<std::string> truth, std::optional<std::string> scene) {
        smql_result* result = nullptr;
        smql_status status;
        {
            py::gil_scoped_release release;
            status = smql_check_ingest(handle(), truth ? truth->c_str() : nullptr, scene ? scene->c_str() : nullptr,
                                       &result);
        }
        check(db_, status);
        return table(result);
    }

private:
    static py::tuple table(smql_result* result) {
        py::list columns, rows;
        for (size_t c = 0; c < smql_column_count(result); ++c) columns.append(smql_column_name(result, c));
        for (size_t r = 0; r < smql_row_count(result); ++r) {
            py::tuple row(smql_column_count(result));
            for (size_t c = 0; c < smql_column_count(result); ++c) {
                const char* text = nullptr;
                double real = 0;
                int64_t integer = 0;
                switch (smql_value_type(result, r, c)) {
                    case SMQL_TEXT:
                        smql_value_text(result, r, c, &text);
                        row[c] = py::str(text);
                        break;
                    case SMQL_INTEGER:
                        smql_value_int64(result, r, c, &integer);
                        row[c] = py::int_(integer);
                        break;
                    case SMQL_REAL:
                        smql_value_double(result, r, c, &real);
                        row[c] = py::float_(real);
                        break;
                    default:
                        row[c] = py::none();
                }
            }
            rows.append(row);
        }
        smql_result_free(result);
        return py::make_tuple(columns, rows);
    }

    smql_db* db_ = nullptr;
};

class Statement {
public:
    Statement(Database& database, const std::string& text) : database_(database) {
        check(database.handle(), smql_prepare(database.handle(), text.c_str(), &stmt_));
    }
    // A statement must be finalized before its handle closes (smql.h); the package finalizes its
    // statements before it closes a connection, so one outliving it is only left unfreed.
    ~Statement() {
        if (database_.isOpen()) smql_finalize(stmt_);
    }
    Statement(const Statement&) = delete;
    Statement& operator=(const Statement&) = delete;

    int parameterCount() const { return smql_bind_parameter_count(stmt_); }

    // None, int, float, str, or a sequence of numbers (a vector for SIMILAR TO ?).
    void bind(int index, const py::handle& value) {
        smql_status status;
        if (value.is_none()) {
            status = smql_bind_null(stmt_, index);
        } else if (py::isinstance<py::bool_>(value) || py::isinstance<py::int_>(value)) {
            int overflow = 0;
            const long long integer = PyLong_AsLongLongAndOverflow(value.ptr(), &overflow);
            if (overflow != 0)
                raise(SMQL_ERROR_INPUT,
                      "input error: parameter " + std::to_string(index) + " is outside 64-bit integers", 0, 0);
            status = smql_bind_int(stmt_, index, integer);
        } else if (py::isinstance<py::float_>(value)) {
            status = smql_bind_double(stmt_, index, value.cast<double>());
        } else if (py::isinstance<py::str>(value)) {
            // A lone surrogate has no UTF-8 form: a DataError, as an out-of-range integer is.
            Py_ssize_t size = 0;
            const char* text = PyUnicode_AsUTF8AndSize(value.ptr(), &size);
            if (!text) {
                PyErr_Clear();
                raise(SMQL_ERROR_INPUT,
                      "input error: parameter " + std::to_string(index) + " is text that has no UTF-8 form", 0, 0);
            }
            status = smql_bind_text(stmt_, index, text);
        } else {
            auto vector = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(value);
            if (!vector || vector.ndim() != 1)
                raise(SMQL_ERROR_MISUSE,
                      "misuse: parameter " + std::to_string(index) + " is neither None, a number, text nor a vector", 0,
                      0);
            status = smql_bind_vector(stmt_, index, vector.data(), static_cast<int>(vector.size()));
        }
        check(database_.handle(), status);
    }
    void reset() {
        check(database_.handle(), smql_reset(stmt_));
        stepped_ = false;
    }

    // One run with these values for the placeholders, in one call (a Python call costs more than
    // the C API's): every row as a tuple (boxes as 7-tuples: cx, cy, cz, sx, sy, sz, yaw), the
    // cursor's description (PEP 249's 7-item column entries; None without columns) and the
    // statement's sentence.
    py::tuple execute(const py::sequence& parameters) {
        if (stepped_) reset();
        smql_clear_bindings(stmt_);
        const auto count = static_cast<int>(parameters.size());
        for (int i = 0; i < count; ++i) bind(i + 1, parameters[i]);
        smql_status status;
        {
            py::gil_scoped_release release;
            status = smql_step(stmt_);
        }
        stepped_ = true;
        check(database_.handle(), status);
        const size_t width = smql_stmt_column_count(stmt_);
        py::object description = py::none();
        if (width > 0) {
            py::tuple columns(width);
            for (size_t c = 0; c < width; ++c)
                columns[c] =
                    py::make_tuple(smql_stmt_column_name(stmt_, c), static_cast<int>(smql_stmt_column_type(stmt_, c)),
                                   py::none(), py::none(), py::none(), py::none(), py::none());
            description = std::move(columns);
        }
        py::list rows;
        for (; status == SMQL_ROW; status = smql_step(stmt_)) rows.append(row(width));
        check(database_.handle(), status);
        const char* message = smql_stmt_message(stmt_);
        return py::make_tuple(description, rows, message ? message : "");
    }

private:
    py::tuple row(size_t width) const {
        py::tuple out(width);
        for (size_t c = 0; c < width; ++c) {
            switch (smql_stmt_value_type(stmt_, c)) {
                case SMQL_INTEGER: {
                    int64_t v = 0;
                    smql_stmt_value_int64(stmt_, c, &v);
                    out[c] = py::int_(v);
                    break;
                }
                case SMQL_REAL: {
                    double v = 0;
                    smql_stmt_value_double(stmt_, c, &v);
                    out[c] = py::float_(v);
                    break;
                }
                case SMQL_TEXT: {
                    const char* v = nullptr;
                    smql_stmt_value_text(stmt_, c, &v);
                    out[c] = py::str(v);
                    break;
                }
                case SMQL_BOX: {
                    smql_box v{};
                    smql_stmt_value_box(stmt_, c, &v);
                    out[c] = boxTuple(v);
                    break;
                }
                default:
                    out[c] = py::none();
            }
        }
        return out;
    }

    Database& database_;
    smql_stmt* stmt_ = nullptr;
    bool stepped_ = false;  // run since the last reset
};

}  // namespace

PYBIND11_MODULE(_smql, m) {
    m.doc() = "smql's C API (smql.h); use the smql package, which builds PEP 249 on it";
    m.def("version", [] { return std::string(smql_version()); });
    m.def("complete", [](const std::string& text) { return smql_complete(text.c_str()) != 0; });
    m.attr("TYPE_NULL") = static_cast<int>(SMQL_NULL);
    m.attr("TYPE_INTEGER") = static_cast<int>(SMQL_INTEGER);
    m.attr("TYPE_REAL") = static_cast<int>(SMQL_REAL);
    m.attr("TYPE_TEXT") = static_cast<int>(SMQL_TEXT);
    m.attr("TYPE_BOX") = static_cast<int>(SMQL_BOX);

    py::class_<Database>(m, "Database")
        .def(py::init<const std::string&, bool>(), py::arg("path"), py::arg("read_only") = false)
        .def("close", &Database::close)
        .def("execute_script", &Database::executeScript)
        .def("interrupt", &Database::interrupt)
        .def("translator", &Database::translator)
        .def("set_translator", &Database::setTranslator, py::arg("url"))
        .def("import_file", &Database::importFile)
        .def("export", &Database::exportScene)
        .def("export_points", &Database::exportPoints)
        .def("ingest", &Database::ingest)
        .def("evaluate", &Database::evaluate)
        .def("check_ingest", &Database::checkIngest);

    // keep_alive: a statement keeps its database open.
    py::class_<Statement>(m, "Statement")
        .def(py::init<Database&, const std::string&>(), py::keep_alive<1, 2>())
        .def_property_readonly("parameter_count", &Statement::parameterCount)
        .def("execute", &Statement::execute);
}
