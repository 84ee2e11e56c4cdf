// MuJoCo 2.2.2 as the adapter uses it: error and warning handlers installed once per process (the
// engine's initialisation), models compiled from an MJCF string through a virtual file system, and
// owning pointers. Nothing here knows the rig.
//
// Why handlers: by default mju_error writes MUJOCO_LOG.TXT, prints, waits for Enter and exits the
// process, and warnings are appended to MUJOCO_LOG.TXT in the working directory. The adapter's error handler throws
// MujocoError instead (MuJoCo is C, but Debian builds it with unwind tables on amd64, so the exception crosses its
// frames: tested in tests/mujoco_error_handling_test.cpp), and its warning handler keeps the text for
// the run's reason. With both installed MuJoCo writes no log file.
#pragma once

#include <mujoco/mujoco.h>

#include <array>
#include <memory>
#include <stdexcept>
#include <string>

namespace ib {

// An mju_error raised inside MuJoCo. The mjData it happened in is not usable afterwards.
class MujocoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Installs the error and warning handlers (once per process; later calls do nothing).
void install_mujoco_handlers();

// The text of the last warning MuJoCo reported on this thread, and forgets it ("" when none).
std::string take_mujoco_warning();

// "MuJoCo 2.2.2", from the library itself.
std::string mujoco_version();

// The name of an mjtWarning, e.g. "mjWARN_BADQACC".
const char* mujoco_warning_name(int warning);

// Watches an mjData's warning counters (MuJoCo counts every warning there, resets the state on a bad
// qpos/qvel/qacc and carries on): each call reports the first warning raised since the previous call.
class MujocoWarningWatch {
 public:
  explicit MujocoWarningWatch(const mjData* data);
  // "MuJoCo warning mjWARN_BADQACC at t = ... s: <MuJoCo's text>", or "" when there is none.
  std::string new_warning(double t);

 private:
  const mjData* data_;
  std::array<int, mjNWARNING> seen_{};
};

struct MujocoModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct MujocoDataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};
using MujocoModelPtr = std::unique_ptr<mjModel, MujocoModelDeleter>;
using MujocoDataPtr = std::unique_ptr<mjData, MujocoDataDeleter>;

// Compiles an MJCF document held in memory (through a heap-allocated mjVFS: nothing is written to disk).
// Throws std::runtime_error with MuJoCo's message when the model does not compile.
MujocoModelPtr compile_mjcf(const std::string& mjcf);

MujocoDataPtr make_data(const mjModel* model);

}  // namespace ib
