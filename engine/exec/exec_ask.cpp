// ASK: runs the question's SMQL with an executor of its own (same read transaction and session),
// then answers in words above its rows.
#include "engine/ask/answer.hpp"
#include "engine/exec/executor.hpp"
#include "model/error.hpp"

namespace smql::exec {

ResultSet Executor::run(const binder::BoundAsk& ask) {
    ResultSet rs;
    if (plan_.asked) {
        try {
            rs = Executor(txn_, session_, *plan_.asked, interrupt_).run();
        } catch (const Error& e) {
            // A name that resolves to nothing (a GUIDE's goal) is the absent thing's doing; an interrupt or a limit
            // is not, and stays the question's error.
            if (auto reply = e.kind() == ErrorKind::Binding ? ask::absentAnswer(ask.translation) : std::nullopt) {
                ResultSet none;
                none.message = ask::message(ask.translation, *reply);
                return none;
            }
            throw ask::failedTranslation(e, ask.translation.smql, std::nullopt);
        }
    }
    rs.message = ask::message(ask.translation, ask::answer(ask.translation, rs, scene().info().name));
    return ask::answeredRows(ask.translation, std::move(rs));
}

}  // namespace smql::exec
