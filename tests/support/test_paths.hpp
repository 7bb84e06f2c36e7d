// test_paths.hpp - where tests find the shared real data, the built plugins
// and the build tree.  Paths come from CMake (tests/CMakeLists.txt).
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace arbor::test {

inline std::filesystem::path shared_dir()
{
    return ARBOR_SHARED_DIR;
}

// A file under ../shared/data; fails the test (not skips) when missing, since
// CI always has ../shared beside the checkout.
inline std::filesystem::path shared_data(const std::string &relative)
{
    const std::filesystem::path p = shared_dir() / "data" / relative;
    EXPECT_TRUE(std::filesystem::exists(p)) << "missing shared data file " << p;
    return p;
}

inline std::filesystem::path plugin_dir()
{
    return ARBOR_PLUGIN_DIR;
}

inline std::filesystem::path binary_dir()
{
    return ARBOR_BINARY_DIR;
}

// A fresh empty folder for the current test under the build tree.
inline std::filesystem::path scratch_dir()
{
    const auto *info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::filesystem::path p = binary_dir() / "test-scratch" /
                              (std::string(info->test_suite_name()) + "." + info->name());
    std::filesystem::remove_all(p);
    std::filesystem::create_directories(p);
    return p;
}

} // namespace arbor::test
