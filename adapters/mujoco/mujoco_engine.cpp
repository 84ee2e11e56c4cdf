#include "adapters/mujoco/mujoco_engine.h"

#include <cstring>
#include <mutex>
#include <sstream>

namespace ib {
namespace {

// The last warning's text, per thread: a run reads it right after the step that raised it.
thread_local std::string last_warning;

// MuJoCo's handler type is a plain function pointer. It must not return: in 2.2.2 mju_error then
// returns to its caller, which carries on past the error (a failed mju_malloc hands back a null
// pointer, seen on this version), so it throws.
[[noreturn]] void throw_mujoco_error(const char* message) {
  throw MujocoError(std::string("MuJoCo error: ") + message);
}

void keep_mujoco_warning(const char* message) { last_warning = message; }

}  // namespace

void install_mujoco_handlers() {
  static std::once_flag installed;
  std::call_once(installed, [] {
    mju_user_error = throw_mujoco_error;
    mju_user_warning = keep_mujoco_warning;
  });
}

std::string take_mujoco_warning() {
  std::string text;
  text.swap(last_warning);
  return text;
}

std::string mujoco_version() { return std::string("MuJoCo ") + mj_versionString(); }

const char* mujoco_warning_name(int warning) {
  switch (warning) {
    case mjWARN_INERTIA:
      return "mjWARN_INERTIA";
    case mjWARN_CONTACTFULL:
      return "mjWARN_CONTACTFULL";
    case mjWARN_CNSTRFULL:
      return "mjWARN_CNSTRFULL";
    case mjWARN_VGEOMFULL:
      return "mjWARN_VGEOMFULL";
    case mjWARN_BADQPOS:
      return "mjWARN_BADQPOS";
    case mjWARN_BADQVEL:
      return "mjWARN_BADQVEL";
    case mjWARN_BADQACC:
      return "mjWARN_BADQACC";
    case mjWARN_BADCTRL:
      return "mjWARN_BADCTRL";
    default:
      return "mjWARN_unknown";
  }
}

MujocoWarningWatch::MujocoWarningWatch(const mjData* data) : data_(data) {
  for (int w = 0; w < mjNWARNING; ++w) seen_[w] = data_->warning[w].number;
}

std::string MujocoWarningWatch::new_warning(double t) {
  std::string reason;
  for (int w = 0; w < mjNWARNING; ++w) {
    const int count = data_->warning[w].number;
    if (count != seen_[w] && reason.empty()) {
      std::ostringstream out;
      out.precision(9);
      out << "MuJoCo warning " << mujoco_warning_name(w) << " at t = " << t << " s";
      // the handler kept MuJoCo's own text (it names the degree of freedom)
      const std::string text = take_mujoco_warning();
      if (!text.empty()) out << ": " << text;
      reason = out.str();
    }
    seen_[w] = count;
  }
  return reason;
}

MujocoModelPtr compile_mjcf(const std::string& mjcf) {
  install_mujoco_handlers();
  // mjVFS holds 2000 file names of 1000 characters: about 2 MB, too much for the stack.
  struct VfsDeleter {
    void operator()(mjVFS* vfs) const {
      mj_deleteVFS(vfs);
      delete vfs;
    }
  };
  std::unique_ptr<mjVFS, VfsDeleter> vfs(new mjVFS);
  mj_defaultVFS(vfs.get());
  const char* name = "impactbench_rig.xml";
  // 2.2.2 has no mj_addBufferVFS: make an empty file of the right size and copy the text into it.
  if (mj_makeEmptyFileVFS(vfs.get(), name, static_cast<int>(mjcf.size())) != 0)
    throw std::runtime_error("MuJoCo: could not create the in-memory model file");
  const int file = mj_findFileVFS(vfs.get(), name);
  if (file < 0) throw std::runtime_error("MuJoCo: the in-memory model file is missing");
  std::memcpy(vfs->filedata[file], mjcf.data(), mjcf.size());
  char error[1024] = "";
  MujocoModelPtr model(mj_loadXML(name, vfs.get(), error, sizeof error));
  if (!model) throw std::runtime_error(std::string("MuJoCo could not compile the model: ") + error);
  return model;
}

MujocoDataPtr make_data(const mjModel* model) {
  install_mujoco_handlers();
  MujocoDataPtr data(mj_makeData(model));
  if (!data) throw std::runtime_error("MuJoCo could not allocate mjData");
  return data;
}

}  // namespace ib
