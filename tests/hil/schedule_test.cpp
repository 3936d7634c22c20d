// The sender schedule (hil_sim/include/ntn/hil/schedule.hpp): the anchor only from a plausible
// frame, integer arithmetic that cannot overflow, and the resync rule (K of the last 2K packets
// dropped on one side with a consistent offset), on synthetic times only: no clock, no socket.
#include "ntn/hil/schedule.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>

namespace schedule_test {

using namespace ntn::hil;
constexpr std::int64_t kP = 1'000'000;  // ns: 1 kHz
constexpr std::int64_t kT = 5'000'000'000;
constexpr int kK = SenderSchedule::kResyncAfter;

OfferResult result(OfferStatus status, std::int64_t frame) {
  OfferResult r;
  r.status = status;
  r.frame = frame;
  return r;
}

// Regression: the frame 18 445 744 073 710 made arrival - frame x period overflow and the
// loop wait ~11 days. Such a frame, or any outside the run or the window, never anchors; a
// plausible one does, to exactly arrival - frame x period (+ period / 2 for the loop's frame 0).
TEST(Schedule, OnlyAPlausibleFrameAnchors) {
  SenderSchedule s(kP, 1000);
  ASSERT_TRUE(s.valid());
  EXPECT_FALSE(s.anchor(18'445'744'073'710, kT));
  EXPECT_FALSE(s.anchor(std::numeric_limits<std::int64_t>::max(), kT));
  EXPECT_FALSE(s.anchor(std::numeric_limits<std::int64_t>::min(), kT));
  EXPECT_FALSE(s.anchor(-1, kT));
  EXPECT_FALSE(s.anchor(1000, kT));                         // beyond the run's last frame
  EXPECT_FALSE(s.anchor(InputGate::kFrameWindow + 1, kT));  // the run has room, the window not
  EXPECT_FALSE(s.anchored());
  EXPECT_EQ(s.epoch_ns(), -1);
  EXPECT_TRUE(s.anchor(7, kT));
  EXPECT_EQ(s.sender_epoch_ns(), kT - 7 * kP);
  EXPECT_EQ(s.epoch_ns(), kT - 7 * kP + kP / 2);
  EXPECT_EQ(s.anchor_frame(), 7);
  EXPECT_FALSE(s.anchor(8, kT + kP));  // the first packet only
  EXPECT_EQ(s.take_flags(), 0);
}

// Every product and difference is checked: a run whose length in ns does not fit with room is
// refused when the schedule is made; times at the ends of int64 leave it unanchored.
TEST(Schedule, ArithmeticIsChecked) {
  EXPECT_FALSE(SenderSchedule(0, 10).valid());
  EXPECT_FALSE(SenderSchedule(kP, 0).valid());
  EXPECT_FALSE(SenderSchedule(kP, SenderSchedule::kMaxSpan / kP + 1).valid());
  EXPECT_TRUE(SenderSchedule(kP, SenderSchedule::kMaxSpan / kP).valid());
  EXPECT_FALSE(SenderSchedule(kP, 10, -1).valid());
  EXPECT_FALSE(SenderSchedule(kP, 10, SenderSchedule::kMaxResyncAfter + 1).valid());
  const std::int64_t frames = SenderSchedule::kMaxSpan / kP;
  SenderSchedule s(kP, frames);
  EXPECT_FALSE(s.anchor(1000, std::numeric_limits<std::int64_t>::min(), 1000));
  EXPECT_FALSE(s.anchor(0, std::numeric_limits<std::int64_t>::max(), 0));
  EXPECT_TRUE(s.anchor(1000, 0, 1000));
  EXPECT_EQ(s.sender_epoch_ns(), -1000 * kP);
  // Resync candidates whose times would overflow are ignored, not taken.
  for (int i = 0; i < 3 * kK; ++i)
    EXPECT_FALSE(s.observe(result(OfferStatus::kTooEarly, 1015), 1000,
                           std::numeric_limits<std::int64_t>::min() + i));
  EXPECT_EQ(s.resyncs(), 0U);
}

// K consecutive too-early packets at one lead: re-anchored to the latest epoch they allow,
// counted, flagged once.
TEST(Schedule, ResyncAfterKConsistentTooEarlyPackets) {
  SenderSchedule s(kP, 1000);
  ASSERT_TRUE(s.anchor(0, kT));
  // The sender is 15 frames ahead: its packet f arrives at E + f P, E = kT - 15 P + 300 us, and
  // the loop reads it at its frame k = f - 15, due at kT + k P + P / 2 (seen 200 us later).
  const std::int64_t e = kT - 15 * kP + 300'000;
  for (std::int64_t k = 1; k <= kK; ++k) {
    const std::int64_t f = k + 15;
    const std::int64_t seen = kT + k * kP + kP / 2 + (k == 3 ? 50'000 : 200'000);
    ASSERT_LT(e + f * kP, seen);
    EXPECT_EQ(s.observe(result(OfferStatus::kTooEarly, f), k, seen), k == kK) << k;
  }
  EXPECT_EQ(s.resyncs(), 1U);
  EXPECT_EQ(s.last_resync_frame(), kK);
  // min over the packets of seen - f P: frame 3's, seen 50 us after its deadline.
  EXPECT_EQ(s.sender_epoch_ns(), kT + 3 * kP + kP / 2 + 50'000 - 18 * kP);
  EXPECT_EQ(s.take_flags(), flag::kResync);
  EXPECT_EQ(s.take_flags(), 0);
  // The packets that follow on time (sent at E + f P) arrive at least half a period before their
  // frame's new deadline: jitter below half a period makes none late.
  for (std::int64_t f = 30; f < 40; ++f)
    EXPECT_LE(e + f * kP, s.epoch_ns() + f * kP - kP / 2);
}

// The same on the late side: a sender that stalled once and goes on 30 frames behind.
TEST(Schedule, ResyncAfterKConsistentLatePackets) {
  SenderSchedule s(kP, 1000);
  ASSERT_TRUE(s.anchor(0, kT));
  for (std::int64_t k = 100; k < 100 + kK; ++k) {
    const std::int64_t f = k - 30;
    EXPECT_EQ(s.observe(result(OfferStatus::kLate, f), k, kT + k * kP + kP / 2), k == 100 + kK - 1);
  }
  EXPECT_EQ(s.resyncs(), 1U);
  EXPECT_EQ(s.sender_epoch_ns(), kT + 30 * kP + kP / 2);
}

// No single packet moves the schedule, nor any number of them while half of the stream is used:
// K - 1 dropped packets and K + 1 used ones, over and over, never resync; nor do packets dropped
// on alternating sides or with leads spread wider than kResyncSpread; other kinds (corrupt,
// duplicate, out of the run ...) change nothing. A majority of the last 2K, K or more, does.
TEST(Schedule, RoguePacketsNeverMoveIt) {
  SenderSchedule s(kP, 100'000);
  ASSERT_TRUE(s.anchor(0, kT));
  const std::int64_t epoch = s.epoch_ns();
  std::int64_t k = 1;
  const auto t = [&] { return kT + k * kP + kP / 2; };
  for (int round = 0; round < 50; ++round, ++k) {
    for (int i = 0; i < kK - 1; ++i)
      EXPECT_FALSE(s.observe(result(OfferStatus::kTooEarly, k + 500), k, t()));
    for (int i = 0; i < kK + 1; ++i)
      EXPECT_FALSE(s.observe(result(OfferStatus::kCurrent, k), k, t()));
  }
  for (int i = 0; i < 10 * kK; ++i, ++k)  // alternating sides
    EXPECT_FALSE(s.observe(
        result(i % 2 ? OfferStatus::kLate : OfferStatus::kTooEarly, i % 2 ? k - 5 : k + 20), k,
        t()));
  for (int i = 0; i < 10 * kK; ++i, ++k)  // leads 10, 12, 14, ...: no consistent offset
    EXPECT_FALSE(s.observe(result(OfferStatus::kTooEarly, k + 10 + 2 * (i % 20)), k, t()));
  for (OfferStatus other :
       {OfferStatus::kCorrupt, OfferStatus::kWrongCount, OfferStatus::kDuplicate,
        OfferStatus::kOutOfRun, OfferStatus::kOutOfWindow, OfferStatus::kFrameEnd}) {
    for (int i = 0; i < 3 * kK; ++i)
      EXPECT_FALSE(s.observe(result(other, k + 100), k, t()));
  }
  // A too-early packet beyond the window (the gate calls that out_of_window) is not a candidate.
  for (int i = 0; i < 3 * kK; ++i)
    EXPECT_FALSE(
        s.observe(result(OfferStatus::kTooEarly, k + InputGate::kFrameWindow + 1), k, t()));
  EXPECT_EQ(s.resyncs(), 0U);
  EXPECT_EQ(s.epoch_ns(), epoch);
  EXPECT_EQ(s.take_flags(), 0);
  // Interleaved packets of other kinds are not counted.
  // (The window holds K of the spread leads above: K + 1 at lead 30 are the majority.)
  for (int i = 0; i <= kK; ++i) {
    EXPECT_EQ(s.observe(result(OfferStatus::kTooEarly, k + 30), k, t()), i == kK);
    (void)s.observe(result(OfferStatus::kDuplicate, k), k, t());
    ++k;
  }
  EXPECT_EQ(s.resyncs(), 1U);
  // K dropped and K used, interleaved: no majority, no resync; K + 1 dropped and K - 1 used in
  // the window: a resync at the (K + 1)-th.
  for (int i = 0; i < kK; ++i, ++k) {
    EXPECT_FALSE(s.observe(result(OfferStatus::kCurrent, k), k, t()));
    EXPECT_FALSE(s.observe(result(OfferStatus::kLate, k - 3), k, t()));
  }
  EXPECT_TRUE(s.observe(result(OfferStatus::kLate, k - 3), k, t()));
  EXPECT_EQ(s.resyncs(), 2U);
}

// Before any anchor (no packet in the first wait), K consistent packets anchor the schedule; with
// resync off (resync_after 0) only the first packet ever sets it.
TEST(Schedule, LateSenderIsFollowedAndResyncCanBeOff) {
  SenderSchedule s(kP, 1000);
  for (std::int64_t k = 10; k < 10 + kK; ++k)
    (void)s.observe(result(OfferStatus::kLate, k - 3), k, kT + k * kP);
  EXPECT_TRUE(s.anchored());
  EXPECT_EQ(s.resyncs(), 1U);
  SenderSchedule off(kP, 1000, 0);
  ASSERT_TRUE(off.anchor(0, kT));
  for (std::int64_t k = 10; k < 10 + 10 * kK; ++k)
    EXPECT_FALSE(off.observe(result(OfferStatus::kLate, k - 3), k, kT + k * kP));
  EXPECT_EQ(off.resyncs(), 0U);
}

}  // namespace schedule_test
