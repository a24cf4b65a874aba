// The outcome contract of core: the rules that combine outcomes (core/outcome.h), the parts of
// an InvalidInput (core/errors.h), and the one validation mechanism of options structs
// (core/validation.h).
#include "flaplag/core/outcome.h"

#include <gtest/gtest.h>

#include <limits>
#include <optional>
#include <string>

#include "flaplag/core/errors.h"
#include "flaplag/core/validation.h"

namespace flaplag::outcome_test {
namespace {

TEST(Outcome, StartsOkAndUsable) {
  const Outcome o;
  EXPECT_EQ(Status::Ok, o.status);
  EXPECT_EQ("", o.message);
  EXPECT_TRUE(o.notes.empty());
  EXPECT_TRUE(o.IsUsable());
}

TEST(Outcome, OnlyFailedIsUnusable) {
  Outcome o;
  o.status = Status::Warning;
  EXPECT_TRUE(o.IsUsable());
  o.status = Status::Failed;
  EXPECT_FALSE(o.IsUsable());
}

TEST(Outcome, WorseOrdersOkWarningFailed) {
  EXPECT_EQ(Status::Ok, worse(Status::Ok, Status::Ok));
  EXPECT_EQ(Status::Warning, worse(Status::Ok, Status::Warning));
  EXPECT_EQ(Status::Warning, worse(Status::Warning, Status::Ok));
  EXPECT_EQ(Status::Failed, worse(Status::Warning, Status::Failed));
  EXPECT_EQ(Status::Failed, worse(Status::Failed, Status::Ok));
}

TEST(Outcome, WorsenNeverImprovesAndJoinsMessagesInOrder) {
  Outcome o;
  o.Worsen(Status::Warning, "first");
  EXPECT_EQ(Status::Warning, o.status);
  EXPECT_EQ("first", o.message);
  o.Worsen(Status::Ok, "second");  // a remark in the message; the status stays
  EXPECT_EQ(Status::Warning, o.status);
  EXPECT_EQ("first; second", o.message);
  o.Worsen(Status::Failed, "");  // no text: nothing appended
  EXPECT_EQ(Status::Failed, o.status);
  EXPECT_EQ("first; second", o.message);
  o.Worsen(Status::Warning, "third");
  EXPECT_EQ(Status::Failed, o.status);
  EXPECT_EQ("first; second; third", o.message);
}

TEST(Outcome, WorsenOkWithoutTextChangesNothing) {
  Outcome o;
  o.Worsen(Status::Ok, "");
  EXPECT_EQ(Status::Ok, o.status);
  EXPECT_EQ("", o.message);
}

TEST(Outcome, MergeTakesTheWorseStatusTheOtherMessageAndNotes) {
  Outcome base;
  base.Worsen(Status::Warning, "outside the envelope");
  base.Note("n1");
  Outcome other;
  other.status = Status::Failed;
  other.message = "overflow";
  other.Note("n2");
  base.Merge(other);
  EXPECT_EQ(Status::Failed, base.status);
  EXPECT_EQ("outside the envelope; overflow", base.message);
  ASSERT_EQ(2u, base.notes.size());
  EXPECT_EQ("n1", base.notes[0]);
  EXPECT_EQ("n2", base.notes[1]);
  // Merging an ok outcome without a message is a no-op.
  base.Merge(Outcome{});
  EXPECT_EQ(Status::Failed, base.status);
  EXPECT_EQ("outside the envelope; overflow", base.message);
}

TEST(Outcome, IncludeKeepsTheWorstStatusAndTheFirstProblem) {
  Outcome sweep;
  Outcome ok;
  ok.message = "a finding, not a problem";
  sweep.Include(ok, "at mu = 0.1: ");
  EXPECT_EQ(Status::Ok, sweep.status);
  EXPECT_EQ("", sweep.message);
  Outcome warned;
  warned.status = Status::Warning;
  warned.message = "ambiguous";
  sweep.Include(warned, "at mu = 0.2: ");
  Outcome failed;
  failed.status = Status::Failed;
  failed.message = "overflow";
  sweep.Include(failed, "at mu = 0.3: ");
  EXPECT_EQ(Status::Failed, sweep.status);
  EXPECT_EQ("at mu = 0.2: ambiguous", sweep.message);
}

TEST(Outcome, NotesSkipEmptyText) {
  Outcome o;
  o.Note("");
  o.Note("kept");
  ASSERT_EQ(1u, o.notes.size());
  EXPECT_EQ("kept", o.notes[0]);
  EXPECT_EQ(Status::Ok, o.status);
  EXPECT_EQ("", o.message);
}

TEST(InvalidInput, CarriesNameValueAndReasonApart) {
  const InvalidInput e("tolerance", "-1", "must be > 0: and more");
  EXPECT_EQ("tolerance", e.name());
  EXPECT_EQ("-1", e.value());
  EXPECT_EQ("must be > 0: and more", e.reason());
  EXPECT_STREQ("tolerance = -1: must be > 0: and more", e.what());
  // A value containing the separators does not confuse the parts.
  const InvalidInput f("model", "a = b: c", "unknown");
  EXPECT_EQ("a = b: c", f.value());
  EXPECT_EQ("unknown", f.reason());
}

// An options struct as the library writes them.
struct ToyOptions {
  static constexpr Range kToleranceRange{{0.0, 1e-2, true, false}, "in (0, 1e-2]"};
  static constexpr Range kIterationsRange{{1, 1000, false, false}, "1..1000"};
  double tolerance = 1e-6;
  int iterations = 10;
  double low = 0.0, high = 1.0;
  std::optional<InvalidInput> Validate() const {
    return Requirements()
        .InRange("tolerance", tolerance, kToleranceRange)
        .InRange("iterations", iterations, kIterationsRange)
        .Require(low < high, [&] { return InvalidInput("low", "0", "must be below `high`"); })
        .Result();
  }
  bool IsValid(std::string* error) const { return IsValidReport(Validate(), error); }
  void Check() const { ThrowIfInvalid(Validate()); }
};

TEST(Validation, ValidOptionsPassEveryForm) {
  const ToyOptions o;
  EXPECT_FALSE(o.Validate());
  std::string why = "untouched";
  EXPECT_TRUE(o.IsValid(&why));
  EXPECT_EQ("untouched", why);
  EXPECT_TRUE(o.IsValid(nullptr));
  EXPECT_NO_THROW(o.Check());
}

TEST(Validation, TheFirstUnmetRequirementInEveryForm) {
  ToyOptions o;
  o.tolerance = 0.5;
  o.iterations = 0;  // also wrong, but after tolerance
  const std::optional<InvalidInput> p = o.Validate();
  ASSERT_TRUE(p);
  EXPECT_EQ("tolerance", p->name());
  EXPECT_EQ("0.5", p->value());
  EXPECT_EQ("must be in (0, 1e-2]", p->reason());
  std::string why;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_EQ("tolerance = 0.5: must be in (0, 1e-2]", why);
  try {
    o.Check();
    FAIL() << "no throw";
  } catch (const InvalidInput& e) {
    EXPECT_EQ("tolerance", e.name());
    EXPECT_EQ("must be in (0, 1e-2]", e.reason());
  }
  o.tolerance = 1e-2;  // the closed end
  ASSERT_TRUE(o.Validate());
  EXPECT_EQ("iterations", o.Validate()->name());
  EXPECT_EQ("0", o.Validate()->value());
  EXPECT_EQ("must be 1..1000", o.Validate()->reason());
  o.iterations = 1000;
  o.low = 2.0;
  ASSERT_TRUE(o.Validate());
  EXPECT_EQ("low = 0: must be below `high`", std::string(o.Validate()->what()));
}

TEST(Validation, NonFiniteValuesAreOutsideEveryInterval) {
  const Interval any{-std::numeric_limits<double>::infinity(),
                     std::numeric_limits<double>::infinity(), false, false};
  EXPECT_TRUE(any.Contains(0.0));
  EXPECT_FALSE(any.Contains(std::numeric_limits<double>::quiet_NaN()));
  EXPECT_FALSE(any.Contains(std::numeric_limits<double>::infinity()));
  const Interval positive{0.0, std::numeric_limits<double>::infinity(), true, false};
  EXPECT_FALSE(positive.Contains(0.0));
  EXPECT_TRUE(positive.Contains(1e-300));
  ToyOptions o;
  o.tolerance = std::numeric_limits<double>::quiet_NaN();
  ASSERT_TRUE(o.Validate());
  EXPECT_EQ("nan", o.Validate()->value());
}

TEST(Validation, IncludeReportsANestedStructsProblem) {
  ToyOptions inner;
  inner.iterations = -3;
  const std::optional<InvalidInput> p = Requirements()
                                            .Include(inner.Validate())
                                            .InRange("tolerance", 5.0, ToyOptions::kToleranceRange)
                                            .Result();
  ASSERT_TRUE(p);
  EXPECT_EQ("iterations", p->name());
  EXPECT_EQ("-3", p->value());
}

}  // namespace
}  // namespace flaplag::outcome_test
