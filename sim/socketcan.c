/*
 * socketcan.c - the bus model's frames through a SocketCAN raw socket (see socketcan.h).
 */
#include "sim/socketcan.h"

#include <errno.h>
#include <linux/can.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <poll.h>
#include <stdio.h>
#include <string.h>
#include <sys/ioctl.h>
#include <sys/socket.h>

#include "hal_posix/harness.h"
#include <unistd.h>

#define ECHO_TIMEOUT_MS 2000

int sim_socketcan_open(sim_socketcan_t *s, const char *iface, char *err, size_t errlen)
{
    memset(s, 0, sizeof *s);
    s->fd = -1;
    if (strlen(iface) >= IFNAMSIZ || strlen(iface) >= sizeof s->iface) {
        snprintf(err, errlen, "--can: \"%s\" is too long for an interface name", iface);
        return -1;
    }
    snprintf(s->iface, sizeof s->iface, "%s", iface);
    s->fd = socket(PF_CAN, SOCK_RAW, CAN_RAW);
    if (s->fd < 0) {
        snprintf(err, errlen,
                 "--can %s: cannot open a CAN_RAW socket: %s (no SocketCAN in this kernel: "
                 "tools/canvm.py runs agv-sim where there is, docs/socketcan.md)",
                 iface, strerror(errno));
        return -1;
    }
    int one = 1;
    struct ifreq ifr;
    memset(&ifr, 0, sizeof ifr);
    snprintf(ifr.ifr_name, sizeof ifr.ifr_name, "%s", iface);
    struct sockaddr_can addr;
    memset(&addr, 0, sizeof addr);
    addr.can_family = AF_CAN;
    if (setsockopt(s->fd, SOL_CAN_RAW, CAN_RAW_RECV_OWN_MSGS, &one, sizeof one) != 0) {
        snprintf(err, errlen, "--can %s: CAN_RAW_RECV_OWN_MSGS: %s", iface, strerror(errno));
    } else if (ioctl(s->fd, SIOCGIFINDEX, &ifr) != 0) {
        snprintf(err, errlen, "--can %s: no such interface: %s", iface, strerror(errno));
    } else {
        addr.can_ifindex = ifr.ifr_ifindex;
        if (bind(s->fd, (struct sockaddr *)&addr, sizeof addr) == 0)
            return 0;
        snprintf(err, errlen, "--can %s: cannot bind: %s", iface, strerror(errno));
    }
    close(s->fd);
    s->fd = -1;
    return -1;
}

static int failed(sim_socketcan_t *s, const char *fmt, const hal_can_frame_t *f, const char *why)
{
    char hex[17] = "";
    for (uint8_t i = 0; i < f->len && i < 8; i++)
        snprintf(hex + 2 * i, 3, "%02X", f->data[i]);
    snprintf(s->err, sizeof s->err, fmt, s->iface, f->id, hex, why);
    s->failed = 1;
    posix_run_stop(); /* the run loop stops at the failure */
    return -1;
}

/* Wait up to the echo timeout for @p events on the socket; 1 when ready. */
static int wait_for(int fd, short events)
{
    struct pollfd p = {fd, events, 0};
    int rc;
    do
        rc = poll(&p, 1, ECHO_TIMEOUT_MS);
    while (rc < 0 && errno == EINTR);
    return rc > 0;
}

int sim_socketcan_carry(void *ctx, hal_can_t bus, const hal_can_frame_t *sent, hal_can_frame_t *got)
{
    (void)bus;
    sim_socketcan_t *s = ctx;
    if (s->failed)
        return -1;
    struct can_frame cf;
    memset(&cf, 0, sizeof cf);
    cf.can_id = sent->id;
    cf.can_dlc = sent->len;
    memcpy(cf.data, sent->data, sent->len);
    for (;;) {
        ssize_t n = write(s->fd, &cf, sizeof cf);
        if (n == (ssize_t)sizeof cf)
            break;
        if (n < 0 && (errno == ENOBUFS || errno == EAGAIN) && wait_for(s->fd, POLLOUT))
            continue; /* the interface's queue is full (a real, slower bus): wait */
        return failed(s, "--can %s: cannot send %03X#%s: %s", sent,
                      n < 0 ? strerror(errno) : "short write");
    }
    for (;;) {
        if (!wait_for(s->fd, POLLIN))
            return failed(s, "--can %s: %03X#%s: no echo from the kernel within 2 s (%s)", sent,
                          "is the interface up?");
        struct can_frame back;
        struct iovec iov = {&back, sizeof back};
        struct msghdr msg;
        memset(&msg, 0, sizeof msg);
        msg.msg_iov = &iov;
        msg.msg_iovlen = 1;
        ssize_t n = recvmsg(s->fd, &msg, 0);
        if (n < 0 && errno == EINTR)
            continue;
        if (n != (ssize_t)sizeof back)
            return failed(s, "--can %s: %03X#%s: reading the echo: %s", sent,
                          n < 0 ? strerror(errno) : "not a classical CAN frame");
        if (!(msg.msg_flags & MSG_CONFIRM)) {
            s->foreign++; /* someone else's frame on the interface */
            continue;
        }
        if (back.can_id != sent->id || back.can_dlc != sent->len ||
            memcmp(back.data, sent->data, sent->len) != 0)
            return failed(s, "--can %s: %03X#%s came back different (%s)", sent,
                          "the kernel delivered other bytes");
        memset(got, 0, sizeof *got);
        got->id = (uint16_t)(back.can_id & CAN_SFF_MASK);
        got->len = back.can_dlc;
        memcpy(got->data, back.data, back.can_dlc);
        s->frames++;
        return 0;
    }
}

void sim_socketcan_close(sim_socketcan_t *s)
{
    if (s->fd >= 0)
        close(s->fd);
    s->fd = -1;
}
