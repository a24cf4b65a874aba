// flaplag — the outcome every result carries (the model is Ceres' Solver::Summary).
//
// Numerical outcomes are never exceptions: a result derives from Outcome and says how it went
// (status), what went wrong or what it found (message, shown by every front end), and remarks
// that qualify it without lowering its status (notes).  Two rules combine outcomes:
//   Worsen/Merge: a result is never better than what it rests on: the worse status, the other
//     message appended to this one ("; ").
//   Include: a collection (a sweep's points, a study's rows, a map's cells) is as bad as its
//     worst part, and its message is the first problem met, with where it was met.
#pragma once

#include <string>
#include <tuple>
#include <vector>

#include "flaplag/core/fields.h"
#include "flaplag/core/status.h"

namespace flaplag {

// The worse of two statuses (Ok < Warning < Failed).
Status worse(Status a, Status b);

struct Outcome {
  Status status = Status::Ok;
  // Ok: empty, or what the result found (e.g. "stable up to mu_max = 2").  Otherwise what went
  // wrong, each problem once, joined by "; " in the order met.  Field names in backticks.
  std::string message;
  // Remarks that do not lower the status (not part of the message).
  std::vector<std::string> notes;

  // The numbers may be used: Ok or Warning.  Failed results carry no usable numbers.
  bool IsUsable() const { return status != Status::Failed; }

  // status becomes the worse of status and s; `why` (if not empty) is appended to the message.
  void Worsen(Status s, const std::string& why);
  // Worsen(other.status, other.message), and other's notes appended to these.
  void Merge(const Outcome& other);
  // A part of a collection: status becomes the worse of the two; the message, while still
  // empty, becomes where + part.message when the part is not Ok.  Notes are not collected.
  void Include(const Outcome& part, const std::string& where = "");
  // Appends a note (nothing when empty).
  void Note(const std::string& note);
};

// The rows every result's table ends with (core/fields.h).
constexpr auto describe(Tag<Outcome>) {
  return std::make_tuple(
      Field{"status", &Outcome::status, "",
            "how it went: warning: usable numbers with a caveat (message); failed: no usable "
            "numbers"},
      Field{"message", &Outcome::message, "",
            "what went wrong or what was found; empty when there is nothing to say", kFieldMessage},
      Field{"notes", &Outcome::notes, "",
            "remarks that do not lower the status (JSON: absent when there are none)",
            kFieldMessage | kFieldOmitWhenEmpty});
}

}  // namespace flaplag
