// placeholder
#include <gtest/gtest.h>
TEST(Optical, Builds) {}
