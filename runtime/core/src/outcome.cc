// flaplag — the rules that combine outcomes.
#include "flaplag/core/outcome.h"

namespace flaplag {

Status worse(Status a, Status b) { return static_cast<int>(a) >= static_cast<int>(b) ? a : b; }

void Outcome::Worsen(Status s, const std::string& why) {
  status = worse(status, s);
  if (why.empty()) return;
  message = message.empty() ? why : message + "; " + why;
}

void Outcome::Merge(const Outcome& other) {
  Worsen(other.status, other.message);
  notes.insert(notes.end(), other.notes.begin(), other.notes.end());
}

void Outcome::Include(const Outcome& part, const std::string& where) {
  status = worse(status, part.status);
  if (message.empty() && part.status != Status::Ok) message = where + part.message;
}

void Outcome::Note(const std::string& note) {
  if (!note.empty()) notes.push_back(note);
}

}  // namespace flaplag
