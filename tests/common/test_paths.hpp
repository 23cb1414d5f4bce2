#pragma once
// The paths the tests need: this checkout's sample and sources, ../shared/data, and the tools of
// this build. They live in one file CMake generates (build/tests/test_paths.cpp), not in every
// test file's compile flags, so that a test file compiles the same in every checkout and build
// folder, and a compiler cache filled by one clone serves the next.

namespace lidar_sgm {
namespace test {

extern const char* const kSharedDataDir;   ///< ../shared/data beside the checkout, as configured
extern const char* const kSourceDir;       ///< the checkout
extern const char* const kSampleDir;       ///< data/sample
extern const char* const kHostileDataDir;  ///< tests/data/hostile: the readers' regression corpus

/// Each tool's executable in this build; "" where the tool is not built.
extern const char* const kDensifyTool;
extern const char* const kDisparityTool;
extern const char* const kBatchTool;
extern const char* const kSynthTool;
extern const char* const kEvalTool;
extern const char* const kBenchTool;
extern const char* const kOcclusionStudyTool;

}  // namespace test
}  // namespace lidar_sgm
