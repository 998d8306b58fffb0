/*
 * harness.c - boards, virtual interrupt controllers, simulated time and the event queue.
 * See hal_posix/harness.h for the model.
 */
#include "hal_posix/harness.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hal/pinmap.h"
#include "hal/preempt.h"
#include "harness_internal.h"

typedef struct {
    bool used;
    uint8_t vector;
    uint8_t bit;
    bool nonmaskable;
    posix_isr_fn fn;
    void *ctx;
    uint32_t count;
} source_t;

typedef struct {
    bool used;
    char name[16];
    bool gie;
    uint8_t isr_depth;
    bool in_nmi;
    uint64_t preempt_points;
    bool woken;
    uint32_t pending;     /* bit i: source i's flag */
    uint32_t enabled;     /* bit i: source i unmasked */
    uint32_t nonmaskable; /* bit i: source i ignores GIE */
    source_t src[POSIX_MAX_SOURCES];
    posix_board_state_t hal; /* per-board HAL state (critical sections, lines, captures) */
} board_t;

typedef struct {
    uint64_t t;
    uint64_t seq; /* the order of scheduling, and the event's id */
    posix_event_fn fn;
    void *ctx;
} event_t;

static board_t boards[POSIX_MAX_BOARDS];
static int n_boards; /* boards[0 .. n_boards - 1] were created since the reset */
static int n_woken;  /* boards whose woken flag is set */
/* Bit b is set whenever board b has a flag raised on an enabled source (pending & enabled);
 * it may stay set after they are taken, until posix_dispatch() looks again. */
static uint32_t live;
static int current = -1;
static uint64_t now_ns;
static uint64_t next_seq;
/*
 * The queue: the events sorted by (t, seq), the latest first and the next one last. A run has
 * a handful queued (one per sensor, clock and bus model; about 7 to 11 in the shipped
 * scenarios) and most are scheduled a little ahead of the others: an insertion scans from the
 * end and usually stops at once, and the next event leaves from the end.
 */
static event_t queue[POSIX_MAX_EVENTS];
static size_t queue_n;
static int watch_board = -1; /* posix_run_steps(): its interrupts end a run of instants */
static bool run_stop;        /* posix_run_steps(): end after this instant */
static bool in_steps;        /* posix_run_steps() is running: posix_advance() may move on */
static uint64_t steps_end;   /* its end */
static uint64_t advances;    /* instants posix_advance() moved on to */
static posix_preempt_hook_fn preempt_hook;
static void *preempt_ctx;
volatile int hal_preempt_armed;

static void dispatch(board_t *bd, int b);

static void harness_die(const char *what, int value)
{
    fprintf(stderr, "harness: %s (%d)\n", what, value);
    abort();
}

static board_t *board_at(int b)
{
    /* boards[0 .. n_boards - 1] are all in use: a board lives until posix_reset() */
    if ((unsigned)b >= (unsigned)n_boards)
        harness_die("no such board", b);
    return &boards[b];
}

void posix_reset(void)
{
    memset(boards, 0, sizeof boards);
    n_boards = 0;
    n_woken = 0;
    live = 0;
    current = -1;
    now_ns = 0;
    next_seq = 0;
    queue_n = 0;
    watch_board = -1;
    run_stop = false;
    in_steps = false;
    advances = 0;
    preempt_hook = NULL;
    preempt_ctx = NULL;
    hal_preempt_armed = 0;
    posix_console_redirect(NULL, NULL);
    posix_can_reset();
    posix_clock_signal_reset();
    posix_uart_reset();
}

int posix_board_create(const char *name)
{
    for (int b = 0; b < POSIX_MAX_BOARDS; b++) {
        if (!boards[b].used) {
            memset(&boards[b], 0, sizeof boards[b]);
            boards[b].used = true;
            if (b >= n_boards)
                n_boards = b + 1;
            snprintf(boards[b].name, sizeof boards[b].name, "%s", name ? name : "board");
            return b;
        }
    }
    return -1;
}

void posix_board_select(int board)
{
    (void)board_at(board);
    current = board;
}

int posix_board_current(void)
{
    /* Unit tests call firmware without a harness set up: give them a default board. */
    if (current < 0) {
        int b = posix_board_create("default");
        if (b < 0)
            harness_die("cannot create the default board", b);
        current = b;
    }
    return current;
}

const char *posix_board_name(int board)
{
    return board_at(board)->name;
}

void posix_board_wake(int board)
{
    board_t *bd = board_at(board);
    n_woken += !bd->woken;
    bd->woken = true;
}

bool posix_board_take_wake(int board)
{
    board_t *bd = board_at(board);
    bool w = bd->woken;
    n_woken -= w;
    bd->woken = false;
    return w;
}

posix_board_state_t *posix_board_state(int board)
{
    return &board_at(board)->hal;
}

/* The current board (a valid one: posix_board_select() checked it, or it was just created). */
static board_t *current_board(void)
{
    return &boards[posix_board_current()];
}

bool posix_current_set_gie(bool gie)
{
    board_t *bd = current_board();
    bool was = bd->gie;
    bd->gie = gie;
    return was;
}

bool posix_current_gie(void)
{
    return current_board()->gie;
}

posix_board_state_t *posix_current_state(void)
{
    return &current_board()->hal;
}

void posix_current_dispatch(void)
{
    int b = posix_board_current();
    if (boards[b].pending & boards[b].enabled)
        dispatch(&boards[b], b);
}

int posix_source_register(int board, int vector, int bit, bool nonmaskable, posix_isr_fn fn,
                          void *ctx)
{
    if (vector < 0 || vector >= HAL_VEC_COUNT || bit < 0 || bit > 7 || fn == NULL)
        return -1;
    board_t *bd = board_at(board);
    int free_slot = -1;
    for (int i = 0; i < POSIX_MAX_SOURCES; i++) {
        source_t *s = &bd->src[i];
        if (s->used && s->vector == vector && s->bit == bit) {
            s->fn = fn;
            s->ctx = ctx;
            s->nonmaskable = nonmaskable;
            if (nonmaskable)
                bd->nonmaskable |= 1u << i;
            else
                bd->nonmaskable &= ~(1u << i);
            return i;
        }
        if (!s->used && free_slot < 0)
            free_slot = i;
    }
    if (free_slot < 0)
        return -1;
    source_t *s = &bd->src[free_slot];
    memset(s, 0, sizeof *s);
    s->used = true;
    s->vector = (uint8_t)vector;
    s->bit = (uint8_t)bit;
    s->nonmaskable = nonmaskable;
    s->fn = fn;
    s->ctx = ctx;
    uint32_t bitmask = 1u << free_slot;
    bd->pending &= ~bitmask;
    bd->enabled |= bitmask;
    if (nonmaskable)
        bd->nonmaskable |= bitmask;
    else
        bd->nonmaskable &= ~bitmask;
    return free_slot;
}

int posix_source_find(int board, int vector, int bit)
{
    board_t *bd = board_at(board);
    for (int i = 0; i < POSIX_MAX_SOURCES; i++)
        if (bd->src[i].used && bd->src[i].vector == vector && bd->src[i].bit == bit)
            return i;
    return -1;
}

static source_t *source_at(int board, int source)
{
    board_t *bd = board_at(board);
    if (source < 0 || source >= POSIX_MAX_SOURCES || !bd->src[source].used)
        harness_die("no such interrupt source", source);
    return &bd->src[source];
}

void posix_source_raise(int board, int source)
{
    (void)source_at(board, source);
    boards[board].pending |= 1u << source;
    live |= 1u << board;
}

void posix_source_enable(int board, int source, bool enable)
{
    (void)source_at(board, source);
    if (enable) {
        boards[board].enabled |= 1u << source;
        live |= 1u << board;
    } else {
        boards[board].enabled &= ~(1u << source);
    }
}

bool posix_source_pending(int board, int source)
{
    (void)source_at(board, source);
    return (boards[board].pending >> source) & 1u;
}

uint32_t posix_source_count(int board, int source)
{
    return source_at(board, source)->count;
}

bool posix_in_isr(int board)
{
    return board_at(board)->isr_depth > 0;
}

bool posix_gie(int board)
{
    return board_at(board)->gie;
}

/* The highest-priority source among the deliverable ones @p m (several bits). */
static int pick(const board_t *bd, uint32_t m)
{
    int best = __builtin_ctz(m);
    for (m &= m - 1; m; m &= m - 1) {
        int i = __builtin_ctz(m);
        const source_t *s = &bd->src[i], *b = &bd->src[best];
        if (s->vector > b->vector || (s->vector == b->vector && s->bit < b->bit))
            best = i;
    }
    return best;
}

/* Interrupt entry (GIE cleared by the CPU), source @p s's handler on board @p b, RETI (the
 * status register, hence GIE, back from the stack). */
static inline void take(board_t *bd, int b, source_t *s)
{
    s->count++;
    bool saved_gie = bd->gie;
    bool saved_nmi = bd->in_nmi;
    int saved_current = current;
    bd->gie = false;
    if (s->nonmaskable)
        bd->in_nmi = true;
    bd->isr_depth++;
    current = b;
    s->fn(s->ctx);
    current = saved_current;
    bd->isr_depth--;
    bd->in_nmi = saved_nmi;
    bd->gie = saved_gie;
}

/* Deliver board @p b's pending interrupts (board valid). */
static void dispatch(board_t *bd, int b)
{
    uint32_t m;
    while ((m = bd->pending & bd->enabled) != 0) { /* the common case: nothing (more) */
        if (!bd->gie) /* only the NMI's sources get through, and not into an NMI */
            m = bd->in_nmi ? 0u : m & bd->nonmaskable;
        else if (bd->in_nmi)
            m &= ~bd->nonmaskable;
        if (m == 0)
            return;
        int i = (m & (m - 1)) ? pick(bd, m) : __builtin_ctz(m);
        source_t *s = &bd->src[i];
        if (b == watch_board)
            run_stop = true;
        bd->pending &= ~(1u << i); /* the flag, cleared by the shim */
        take(bd, b, s);
    }
}

void posix_dispatch(void)
{
    if (live == 0)
        return; /* the common case: no flag raised on an enabled source since the last look */
    board_t *bd = boards;
    for (int b = 0; b < n_boards; b++, bd++)
        if (bd->pending & bd->enabled)
            dispatch(bd, b);
    uint32_t still = 0; /* what stays (masked by GIE, or raised meanwhile) */
    bd = boards;
    for (int b = 0; b < n_boards; b++, bd++)
        if (bd->pending & bd->enabled)
            still |= 1u << b;
    live = still;
}

void hal_preempt_point(void)
{
    int b = current >= 0 ? current : posix_board_current();
    board_t *bd = &boards[b];
    bd->preempt_points++;
    if (preempt_hook)
        preempt_hook(preempt_ctx, b, bd->preempt_points);
    if (bd->pending & bd->enabled)
        dispatch(bd, b);
}

void posix_set_preempt_hook(posix_preempt_hook_fn fn, void *ctx)
{
    preempt_hook = fn;
    preempt_ctx = ctx;
    hal_preempt_armed = fn != NULL;
}

uint64_t posix_preempt_points(int board)
{
    return board_at(board)->preempt_points;
}

/* ---- time and events: a queue sorted by (t, seq) ---- */

/* Does the queued event @p e come before (t, seq)? */
static bool earlier(const event_t *e, uint64_t t, uint64_t seq)
{
    return e->t < t || (e->t == t && e->seq < seq);
}

/* Remove the event at @p i. */
static void queue_remove(size_t i)
{
    queue_n--;
    memmove(&queue[i], &queue[i + 1], (queue_n - i) * sizeof queue[0]);
}

uint64_t posix_now_ns(void)
{
    return now_ns;
}

uint64_t posix_schedule(uint64_t t_ns, posix_event_fn fn, void *ctx)
{
    if (fn == NULL || t_ns < now_ns || queue_n >= POSIX_MAX_EVENTS)
        return 0;
    uint64_t id = ++next_seq;
    size_t i = queue_n++;
    for (; i > 0 && earlier(&queue[i - 1], t_ns, id); i--)
        queue[i] = queue[i - 1];
    queue[i].t = t_ns;
    queue[i].seq = id;
    queue[i].fn = fn;
    queue[i].ctx = ctx;
    return id;
}

bool posix_cancel(uint64_t id)
{
    for (size_t i = queue_n; i-- > 0;) {
        if (queue[i].seq == id) {
            queue_remove(i);
            return true;
        }
    }
    return false;
}

uint64_t posix_next_event_ns(void)
{
    return queue_n ? queue[queue_n - 1].t : UINT64_MAX;
}

/* Run the next event (queue_n > 0) and deliver the interrupts it raised. */
static void run_first(void)
{
    const event_t *e = &queue[--queue_n];
    uint64_t t = e->t;
    posix_event_fn fn = e->fn;
    void *ctx = e->ctx;
    now_ns = t;
    fn(ctx, t);
    posix_dispatch();
}

uint64_t posix_run_until(uint64_t t_ns)
{
    uint64_t n = 0;
    while (queue_n && queue[queue_n - 1].t <= t_ns) {
        run_first();
        n++;
    }
    if (t_ns > now_ns)
        now_ns = t_ns;
    return n;
}

void posix_run_stop(void)
{
    run_stop = true;
}

static bool any_woken(void)
{
    return n_woken != 0;
}

uint64_t posix_run_steps(uint64_t end_ns, int board)
{
    uint64_t n = 0, advanced = advances;
    watch_board = board;
    run_stop = false;
    in_steps = true;
    steps_end = end_ns;
    while (queue_n && queue[queue_n - 1].t <= end_ns) {
        uint64_t instant = queue[queue_n - 1].t;
        while (queue_n && queue[queue_n - 1].t == instant) {
            run_first();
            n++;
        }
        if (any_woken() || run_stop)
            break;
    }
    in_steps = false;
    watch_board = -1;
    return n + (advances - advanced);
}

/* posix_advance()'s work. */
static inline bool advance(uint64_t t_ns)
{
    if (!in_steps || t_ns <= now_ns || t_ns > steps_end)
        return false;
    posix_dispatch();
    if (run_stop || any_woken() || (queue_n && queue[queue_n - 1].t <= t_ns))
        return false;
    now_ns = t_ns;
    advances++;
    return true;
}

bool posix_advance_raise(uint64_t t_ns, int board, int source)
{
    source_t *s = source_at(board, source);
    board_t *bd = &boards[board];
    if (!advance(t_ns))
        return false;
    uint32_t bit = 1u << source;
    if (!bd->gie || bd->in_nmi || s->nonmaskable || !(bd->enabled & bit) ||
        (bd->pending & bd->enabled) || board == watch_board) {
        bd->pending |= bit; /* the general way: priorities, masks, the NMI, the watch */
        live |= 1u << board;
        dispatch(bd, board);
        return true;
    }
    take(bd, board, s); /* the common case: the only deliverable source, GIE set */
    if (bd->pending & bd->enabled)
        dispatch(bd, board); /* what the handler raised on its own board */
    return true;
}

bool posix_advance(uint64_t t_ns)
{
    return advance(t_ns);
}
