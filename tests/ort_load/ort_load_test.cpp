// SPDX-License-Identifier: MIT
// The run-time onnxruntime loader of the pip wheel (runtime/model/ort_so_load.cpp, built here
// with SILK_ORT_RUNTIME_LOAD and a probe path beside this executable): a failed load is tried
// again on the next call (issue 35: installing onnxruntime after a failure still said "No such
// file" for the life of the process), a release older than the headers is refused in Silk's
// words alone (it printed its own line to stderr), and the current one then loads.
#include <dlfcn.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "runtime/model/ort_dll_load.h"

namespace {

namespace fs = std::filesystem;

fs::path ProbeDir() {  // SILK_ORT_RELATIVE_PATH's folder, beside this executable
  Dl_info info{};
  dladdr(reinterpret_cast<void*>(&ProbeDir), &info);
  return fs::canonical(info.dli_fname).parent_path() / "ort_load_probe";
}

// A new file (new inode) at the probe path, as an installer would leave it.
void Install(const fs::path& from) {
  const fs::path dir = ProbeDir();
  fs::create_directories(dir);
  fs::copy_file(from, dir / ".partial", fs::copy_options::overwrite_existing);
  fs::rename(dir / ".partial", dir / "libonnxruntime.so");
}

TEST(OrtRuntimeLoad, AFailureIsRetriedAndATooOldReleaseIsRefusedInSilksWordsOnly) {
  fs::remove_all(ProbeDir());
  const silk::Status missing = silk::LoadOnnxRuntimeLibrary();
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.message().find("cannot load onnxruntime"), std::string::npos) << missing.ToString();

  Install(SILK_TEST_OLD_ORT);
  testing::internal::CaptureStderr();
  const silk::Status old = silk::LoadOnnxRuntimeLibrary();
  const std::string printed = testing::internal::GetCapturedStderr();
  ASSERT_FALSE(old.ok());
  EXPECT_NE(old.message().find("onnxruntime 1.10.0 is too old"), std::string::npos) << old.ToString();
  EXPECT_NE(old.message().find("libonnxruntime.so"), std::string::npos) << old.ToString();
  EXPECT_EQ(printed, "") << "the library spoke for itself";

  Install(SILK_TEST_REAL_ORT);
  const silk::Status loaded = silk::LoadOnnxRuntimeLibrary();
  EXPECT_TRUE(loaded.ok()) << loaded.ToString();
  EXPECT_TRUE(silk::LoadOnnxRuntimeLibrary().ok());  // success is kept
  fs::remove_all(ProbeDir());
}

}  // namespace
