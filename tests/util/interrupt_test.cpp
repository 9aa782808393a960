// Interrupts (util/interrupt.h) and quoting input in messages (util/error.h).
#include "pelage/util/interrupt.h"

#include <gtest/gtest.h>
#include <signal.h>

#include <string>

#include "pelage/util/error.h"

namespace pelage {
namespace {

int gPolls = 0;
void countingPoll() {
  if (++gPolls == 3) throw Interrupted(0);
}

TEST(Interrupt, NothingAskedNothingThrown) {
  clearInterrupt();
  EXPECT_NO_THROW(checkInterrupt());
}

TEST(Interrupt, APollIsAskedAtEveryCheckAndMayStop) {
  clearInterrupt();
  gPolls = 0;
  setInterruptPoll(countingPoll);
  EXPECT_NO_THROW(checkInterrupt());
  EXPECT_NO_THROW(checkInterrupt());
  EXPECT_THROW(checkInterrupt(), Interrupted);
  setInterruptPoll(nullptr);
  EXPECT_NO_THROW(checkInterrupt());
  EXPECT_EQ(gPolls, 3);
}

TEST(Interrupt, ACaughtSignalStopsAtTheNextCheckWithItsNumber) {
  struct sigaction oldInt {
  }, oldTerm{};
  ::sigaction(SIGINT, nullptr, &oldInt);
  ::sigaction(SIGTERM, nullptr, &oldTerm);
  catchInterrupts();
  for (const int sig : {SIGINT, SIGTERM}) {
    clearInterrupt();
    ASSERT_EQ(::raise(sig), 0);  // the process goes on: the stop waits for a check
    try {
      checkInterrupt();
      ADD_FAILURE() << "no stop after signal " << sig;
    } catch (const Interrupted& e) {
      EXPECT_EQ(e.signal(), sig);
      EXPECT_STREQ(e.what(), "interrupted");
    }
    EXPECT_THROW(checkInterrupt(), Interrupted);  // until cleared
  }
  clearInterrupt();
  EXPECT_NO_THROW(checkInterrupt());
  ::sigaction(SIGINT, &oldInt, nullptr);
  ::sigaction(SIGTERM, &oldTerm, nullptr);
}

TEST(Excerpt, ShortInputStaysLongInputIsCutWithItsLength) {
  EXPECT_EQ(excerpt("Fox.glb"), "Fox.glb");
  EXPECT_EQ(excerpt("a\nb\x01"), "a\\x0ab\\x01");
  const std::string big(2040164, 'Q');
  const std::string q = excerpt(big);
  EXPECT_EQ(q, std::string(kMaxQuotedChars, 'Q') + "... (2040164 bytes)");
  EXPECT_EQ(excerpt("abcdef", 3), "abc... (6 bytes)");
  EXPECT_EQ(excerpt("Fuß"), "Fuß");  // UTF-8 stays
}

TEST(Excerpt, LongWordsOfAnotherLibrarysMessageAreCut) {
  const std::string uri = "data:application/octet-stream;base64," + std::string(100000, 'A');
  const std::string msg = "Failed to load external 'uri' for buffer[0] " + uri + "\nnext line";
  const std::string s = shortenLongWords(msg);
  EXPECT_LT(s.size(), 200u);
  EXPECT_NE(s.find("Failed to load external 'uri' for buffer[0] data:application"),
            std::string::npos);
  EXPECT_NE(s.find("(100037 bytes)\nnext line"), std::string::npos) << s;
}

}  // namespace
}  // namespace pelage
