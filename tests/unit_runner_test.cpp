// The one runner (harness/jobs/unit_source.h) on sources of trivial units, with real processes: the
// costliest ready unit first whatever its source, no source waits for another, a unit waits for what it
// depends on, a time limit stops a unit, a write error comes back with its message.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include "harness/jobs/unit_source.h"
#include "harness/jobs/worker_process.h"

namespace ib {
namespace unit_runner_test {

using Clock = std::chrono::steady_clock;

// A unit: its cost, how long its process sleeps, and the unit it waits for ("" none).
struct FakeUnit {
  FakeUnit(std::string unit_id, double unit_cost, double unit_sleep_s = 0, std::string unit_after = "")
      : id(std::move(unit_id)), cost(unit_cost), sleep_s(unit_sleep_s), after(std::move(unit_after)) {}
  std::string id;
  double cost = 1;
  double sleep_s = 0;
  std::string after;
};

// Starts its units costliest first among the ready ones; notes the order they started and when they ended.
class FakeSource : public UnitSource {
 public:
  FakeSource(std::vector<FakeUnit> units, std::vector<std::string>* started, std::map<std::string, double>* ended_at)
      : pending_(std::move(units)), started_(started), ended_at_(ended_at) {}
  std::optional<double> next_cost() override {
    next_ = -1;
    for (int i = 0; i < static_cast<int>(pending_.size()); ++i)
      if ((pending_[i].after.empty() || ended_at_->count(pending_[i].after)) &&
          (next_ < 0 || pending_[i].cost > pending_[next_].cost))
        next_ = i;
    if (next_ < 0) return std::nullopt;
    return pending_[next_].cost;
  }
  std::string start_next(ProcessPool& pool) override {
    const FakeUnit unit = pending_[next_];
    pending_.erase(pending_.begin() + next_);
    started_->push_back(unit.id);
    pool.start({unit.id, time_limit_s, "", false}, [unit](int) {
      std::this_thread::sleep_for(std::chrono::duration<double>(unit.sleep_s));
      _exit(0);
    });
    return unit.id;
  }
  void ended(const ProcessEnd& end) override {
    (*ended_at_)[end.unit] = std::chrono::duration<double>(Clock::now() - start_).count();
    ends.push_back(end);
  }
  double time_limit_s = 0;
  std::vector<ProcessEnd> ends;

 private:
  std::vector<FakeUnit> pending_;
  std::vector<std::string>* started_;
  std::map<std::string, double>* ended_at_;
  int next_ = -1;
  Clock::time_point start_ = Clock::now();
};

TEST(UnitRunner, TheCostliestReadyUnitStartsFirstWhateverItsSource) {
  std::vector<std::string> started;
  std::map<std::string, double> ended_at;
  FakeSource a({{"a1", 1}, {"a5", 5}}, &started, &ended_at);
  FakeSource b({{"b3", 3}}, &started, &ended_at);
  run_units({&a, &b}, 1);
  EXPECT_EQ(started, (std::vector<std::string>{"a5", "b3", "a1"}));
  EXPECT_EQ(ended_at.size(), 3u);
}

TEST(UnitRunner, NoSourceWaitsForAnotherToEnd) {
  // Two workers: while a's long unit runs, every one of b's short units runs on the other worker.
  std::vector<std::string> started;
  std::map<std::string, double> ended_at;
  FakeSource a({{"long", 10, 2.0}}, &started, &ended_at);
  FakeSource b({{"s1", 1, 0.05}, {"s2", 1, 0.05}, {"s3", 1, 0.05}}, &started, &ended_at);
  run_units({&a, &b}, 2);
  ASSERT_EQ(ended_at.size(), 4u);
  for (const char* id : {"s1", "s2", "s3"}) EXPECT_LT(ended_at[id], ended_at["long"]) << id;
}

TEST(UnitRunner, AUnitWaitsForTheUnitItDependsOn) {
  std::vector<std::string> started;
  std::map<std::string, double> ended_at;
  FakeSource a({{"reference", 1, 0.3}, {"engine", 9, 0, "reference"}}, &started, &ended_at);
  run_units({&a}, 2);  // a free worker does not start the costlier engine unit before its reference ended
  EXPECT_EQ(started, (std::vector<std::string>{"reference", "engine"}));
  EXPECT_GE(ended_at["engine"], ended_at["reference"]);
}

TEST(UnitRunner, AUnitPastItsTimeLimitIsStoppedAndSaysSo) {
  std::vector<std::string> started;
  std::map<std::string, double> ended_at;
  FakeSource a({{"hangs", 1, 30.0}, {"quick", 1, 0}}, &started, &ended_at);
  a.time_limit_s = 0.3;
  const auto t0 = Clock::now();
  run_units({&a}, 2);
  EXPECT_LT(std::chrono::duration<double>(Clock::now() - t0).count(), 10.0);
  ASSERT_EQ(a.ends.size(), 2u);
  for (const ProcessEnd& end : a.ends) {
    if (end.unit == "hangs") {
      EXPECT_TRUE(end.timed_out);
      EXPECT_TRUE(WIFSIGNALED(end.status));
    } else {
      EXPECT_FALSE(end.timed_out);
      EXPECT_TRUE(WIFEXITED(end.status) && WEXITSTATUS(end.status) == 0);
    }
  }
}

TEST(UnitRunner, AWriteErrorComesBackWithItsMessage) {
  ProcessPool pool;
  pool.start({"writer", 0, "", false}, [](int pipe) { send_and_exit(pipe, "cannot write /full/disk/runs.csv"); });
  const std::optional<ProcessEnd> end = pool.wait_end();
  ASSERT_TRUE(end);
  EXPECT_EQ(end->unit, "writer");
  EXPECT_TRUE(WIFEXITED(end->status) && WEXITSTATUS(end->status) == kWorkerOutputError);
  EXPECT_EQ(end->output_error, "cannot write /full/disk/runs.csv");
  EXPECT_FALSE(pool.wait_end());  // none runs
}

}  // namespace unit_runner_test
}  // namespace ib
