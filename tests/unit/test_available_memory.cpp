// The ARBOR_MEMORY_AVAILABLE override: a byte count in digits or with an
// exponent, and a clear refusal of anything else (before 12-06 "60e9" was
// ignored without a word and the machine's own figure used).
#include "core/available_memory.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

using arbor::memory_override_bytes;

TEST(MemoryOverride, TakesDigitsAndExponents)
{
    EXPECT_EQ(memory_override_bytes("3300000000"), 3300000000u);
    EXPECT_EQ(memory_override_bytes("3.3e9"), 3300000000u);
    EXPECT_EQ(memory_override_bytes("60e9"), 60000000000u);
    EXPECT_EQ(memory_override_bytes("0"), 0u);
}

TEST(MemoryOverride, RefusesWhatIsNotAByteCount)
{
    for (const char *bad : {"", "lots", "-5", "0x10", "inf", "nan", " 5", "5 GB", "1e30", "1.2.3"}) {
        try {
            memory_override_bytes(bad);
            ADD_FAILURE() << "accepted \"" << bad << "\"";
        } catch (const std::invalid_argument &e) {
            EXPECT_NE(std::string(e.what()).find(std::string("\"") + bad + "\""), std::string::npos) << e.what();
        }
    }
}
