// Tests of hal/uart.h on the harness (hal/posix/uart.c): the return codes, bytes arriving at
// their bit timing (10 bits per byte at the opened rate), back to back, as interrupts of the
// instance's vector, overruns when the handler is late, and closing.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

extern "C" {
#include "hal/irq.h"
#include "hal/pinmap.h"
#include "hal/uart.h"
#include "hal_posix/harness.h"
}

namespace
{

struct Got {
    uint8_t byte, flags;
    uint64_t t_ns;
    int instance;
};

std::vector<Got> got;

void on_byte0(void *arg, uint8_t b, uint8_t f)
{
    (void)arg;
    got.push_back({b, f, posix_now_ns(), 0});
}

void on_byte1(void *arg, uint8_t b, uint8_t f)
{
    (void)arg;
    got.push_back({b, f, posix_now_ns(), 1});
}

class Uart : public ::testing::Test
{
  protected:
    int b = -1;
    void SetUp() override
    {
        posix_reset();
        got.clear();
        b = posix_board_create("main");
        posix_board_select(b);
    }
};

TEST_F(Uart, ReturnCodes)
{
    EXPECT_EQ(hal_uart_open(2, HAL_UART_BAUD_9600, on_byte0, nullptr), HAL_UART_E_INSTANCE);
    EXPECT_EQ(hal_uart_open(0, 4800, on_byte0, nullptr), HAL_UART_E_BAUD);
    EXPECT_EQ(hal_uart_open(0, HAL_UART_BAUD_9600, nullptr, nullptr), HAL_UART_E_ARG);
    const uint8_t x = 1;
    EXPECT_EQ(posix_uart_send(b, 0, &x, 1, 0), 0u) << "not open: nothing sent";
    EXPECT_EQ(hal_uart_open(0, HAL_UART_BAUD_9600, on_byte0, nullptr), HAL_UART_OK);
    EXPECT_EQ(hal_uart_open(1, HAL_UART_BAUD_115200, on_byte1, nullptr), HAL_UART_OK);
    EXPECT_GE(posix_uart_source(b, 0), 0);
    EXPECT_EQ(posix_source_find(b, HAL_VEC_UART1_RX, 0), posix_uart_source(b, 1));
}

TEST_F(Uart, BytesArriveAtTheirBitTiming)
{
    ASSERT_EQ(hal_uart_open(0, HAL_UART_BAUD_9600, on_byte0, nullptr), HAL_UART_OK);
    hal_irq_enable();
    posix_run_until(500000); // the line starts later than time 0
    const uint8_t s[] = {0x00, 0x5A, 0xFF};
    EXPECT_EQ(posix_uart_send(b, 0, s, 3, 0), 3u);
    // 10 bits at 9600 baud: 1/960 s = 1,041,666.7 ns per byte
    EXPECT_EQ(posix_uart_idle_ns(b, 0), 500000u + 3u * 1041667u);
    posix_run_until(10000000);
    ASSERT_EQ(got.size(), 3u);
    for (int i = 0; i < 3; i++) {
        EXPECT_EQ(got[i].byte, s[i]);
        EXPECT_EQ(got[i].flags, 0);
        EXPECT_EQ(got[i].t_ns, 500000u + (uint64_t)(i + 1) * 1041667u);
    }
    // sent while the line is busy: back to back after the bytes before
    got.clear();
    posix_run_until(20000000);
    EXPECT_EQ(posix_uart_send(b, 0, s, 1, 0), 1u);
    posix_run_until(20500000);
    EXPECT_EQ(posix_uart_send(b, 0, s + 1, 1, HAL_UART_RX_ERROR), 1u);
    posix_run_until(30000000);
    ASSERT_EQ(got.size(), 2u);
    EXPECT_EQ(got[0].t_ns, 20000000u + 1041667u);
    EXPECT_EQ(got[1].t_ns, 20000000u + 2u * 1041667u);
    EXPECT_EQ(got[1].flags, HAL_UART_RX_ERROR);
    // 115200 baud: 86,805.6 ns per byte
    got.clear();
    ASSERT_EQ(hal_uart_open(0, HAL_UART_BAUD_115200, on_byte0, nullptr), HAL_UART_OK);
    EXPECT_EQ(posix_uart_send(b, 0, s, 2, 0), 2u);
    posix_run_until(40000000);
    ASSERT_EQ(got.size(), 2u);
    EXPECT_EQ(got[1].t_ns - got[0].t_ns, 86806u);
}

TEST_F(Uart, ALateHandlerOverrunsTheByteBefore)
{
    ASSERT_EQ(hal_uart_open(0, HAL_UART_BAUD_115200, on_byte0, nullptr), HAL_UART_OK);
    const uint8_t s[] = {0x11, 0x22, 0x33};
    EXPECT_EQ(posix_uart_send(b, 0, s, 3, 0), 3u);
    posix_run_until(1000000); // interrupts disabled: nobody reads
    EXPECT_TRUE(got.empty());
    EXPECT_EQ(posix_uart_overruns(b, 0), 2u);
    EXPECT_EQ(hal_uart_overruns(0), 2u);
    hal_irq_enable();
    ASSERT_EQ(got.size(), 1u);
    EXPECT_EQ(got[0].byte, 0x33);
    EXPECT_EQ(got[0].flags, HAL_UART_RX_ERROR);
}

TEST_F(Uart, InstanceOneIsServedFirstAndCloseStops)
{
    ASSERT_EQ(hal_uart_open(0, HAL_UART_BAUD_9600, on_byte0, nullptr), HAL_UART_OK);
    ASSERT_EQ(hal_uart_open(1, HAL_UART_BAUD_9600, on_byte1, nullptr), HAL_UART_OK);
    const uint8_t s[] = {0xA0, 0xA1};
    posix_uart_send(b, 0, s, 1, 0);
    posix_uart_send(b, 1, s + 1, 1, 0);
    posix_run_until(2000000); // both pending, interrupts still disabled
    hal_irq_enable();
    ASSERT_EQ(got.size(), 2u);
    EXPECT_EQ(got[0].instance, 1) << "vector 23 (USCIAB0RX) above 17 (USCIAB1RX)";
    EXPECT_EQ(got[1].instance, 0);
    got.clear();
    posix_uart_send(b, 0, s, 2, 0);
    hal_uart_close(0);
    posix_run_until(10000000);
    EXPECT_TRUE(got.empty());
    EXPECT_EQ(posix_uart_send(b, 0, s, 1, 0), 0u);
    EXPECT_EQ(posix_uart_source(b, 0), -1);
}

TEST_F(Uart, TheLineHoldsAFiniteQueue)
{
    ASSERT_EQ(hal_uart_open(0, HAL_UART_BAUD_9600, on_byte0, nullptr), HAL_UART_OK);
    std::vector<uint8_t> s(POSIX_UART_QUEUE + 10, 0x42);
    EXPECT_EQ(posix_uart_send(b, 0, s.data(), s.size(), 0), (size_t)POSIX_UART_QUEUE);
}

} // namespace
