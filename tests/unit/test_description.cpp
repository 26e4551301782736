#include <gtest/gtest.h>
TEST(Description, Placeholder) {}
