/* Terminal I/O for the interactive viewer: see termio.h. */
#define _DEFAULT_SOURCE
#define _POSIX_C_SOURCE 200809L
#include "termio.h"

#include <errno.h>
#include <poll.h>
#include <signal.h>
#include <string.h>
#include <sys/ioctl.h>
#include <termios.h>
#include <unistd.h>

static volatile sig_atomic_t got_quit, got_winch;
static struct termios saved_termios;
static char out[MC_TERM_OUT_BYTES];
static size_t out_len;

/* ---- output ------------------------------------------------------------------------------------- */

/* Write everything, retrying after signals: a frame cut in the middle of an escape would garble the
 * screen. Returns -1 only when the terminal is gone. */
int mc_tio_write(const char *p, size_t n)
{
    while (n > 0) {
        ssize_t k = write(STDOUT_FILENO, p, n);
        if (k < 0) {
            if (errno == EINTR || errno == EAGAIN) continue;
            return -1;
        }
        p += k;
        n -= (size_t)k;
    }
    return 0;
}

void mc_tio_begin(void) { out_len = 0; }

int mc_tio_flush(void) { return mc_tio_write(out, out_len); }

void mc_tio_put(const char *s, size_t n)
{
    if (n > sizeof out - out_len) n = sizeof out - out_len;   /* the viewer's layout keeps this from happening */
    memcpy(out + out_len, s, n);
    out_len += n;
}

void mc_tio_put_str(const char *s) { mc_tio_put(s, strlen(s)); }

/* snprintf would be called 150 000 times a frame; this is the hot path of the output. */
void mc_tio_put_uint(unsigned v)
{
    char digits[10];
    int n = 0;
    do digits[n++] = (char)('0' + v % 10); while (v /= 10);
    while (n > 0 && out_len < sizeof out) out[out_len++] = digits[--n];
}

void mc_tio_put_move(int row, int col)
{
    mc_tio_put_str("\x1b[");
    mc_tio_put_uint((unsigned)row + 1);
    mc_tio_put_str(";");
    mc_tio_put_uint((unsigned)col + 1);
    mc_tio_put_str("H");
}

void mc_tio_put_rgb(uint32_t rgb)
{
    mc_tio_put_uint(rgb >> 16);
    mc_tio_put_str(";");
    mc_tio_put_uint((rgb >> 8) & 0xFF);
    mc_tio_put_str(";");
    mc_tio_put_uint(rgb & 0xFF);
}

/* ---- terminal setup ------------------------------------------------------------------------------ */

/* got_quit holds the signal number, so the exit status can say which one ended the viewer. */
static void on_signal(int sig)
{
    if (sig == SIGWINCH) got_winch = 1;
    else got_quit = sig;
}

/* No SA_RESTART: a signal must wake poll() so the main loop sees the flag at once. */
static void install_signals(void)
{
    static const int sigs[] = {SIGINT, SIGTERM, SIGHUP, SIGWINCH};
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    for (size_t i = 0; i < sizeof sigs / sizeof sigs[0]; i++) sigaction(sigs[i], &sa, NULL);
}

static void restore_signals(void)
{
    signal(SIGINT, SIG_DFL);
    signal(SIGTERM, SIG_DFL);
    signal(SIGHUP, SIG_DFL);
    signal(SIGWINCH, SIG_DFL);
}

/* Raw input: bytes as typed, no echo; Ctrl-C arrives as byte 3 (ISIG off) so it quits through the
 * same path as 'q', and Ctrl-S cannot freeze the output (IXON off). read() never blocks (VMIN=0). */
static int enter_raw_mode(void)
{
    if (tcgetattr(STDIN_FILENO, &saved_termios) != 0) return -1;
    struct termios raw = saved_termios;
    raw.c_iflag &= ~(tcflag_t)(IXON | ICRNL | INLCR | IGNCR | ISTRIP | BRKINT | PARMRK);
    raw.c_lflag &= ~(tcflag_t)(ECHO | ECHONL | ICANON | ISIG | IEXTEN);
    raw.c_cc[VMIN] = 0;
    raw.c_cc[VTIME] = 0;
    return tcsetattr(STDIN_FILENO, TCSANOW, &raw);
}

int mc_tio_enter(void)
{
    if (enter_raw_mode() != 0) return -1;
    got_quit = got_winch = 0;
    install_signals();
    mc_tio_write("\x1b[?1049h\x1b[?25l", 14);   /* alternate screen (the shell's comes back), cursor hidden */
    return 0;
}

void mc_tio_leave(void)
{
    static const char seq[] = "\x1b[0m\x1b[?25h\x1b[?1049l";
    mc_tio_write(seq, sizeof seq - 1);
    tcsetattr(STDIN_FILENO, TCSAFLUSH, &saved_termios);   /* FLUSH: unread keys do not reach the shell */
    restore_signals();
}

int mc_tio_quit_signal(void) { return got_quit; }

int mc_tio_resized(void)
{
    if (!got_winch) return 0;
    got_winch = 0;
    return 1;
}

void mc_tio_size(int *cols, int *rows)
{
    struct winsize ws;
    *cols = 80;
    *rows = 24;
    if (ioctl(STDOUT_FILENO, TIOCGWINSZ, &ws) == 0 && ws.ws_col > 0 && ws.ws_row > 0) {
        *cols = ws.ws_col;
        *rows = ws.ws_row;
    }
}

/* ---- input -------------------------------------------------------------------------------------- */

int mc_tio_input_waiting(void)
{
    if (got_quit || got_winch) return 1;
    struct pollfd p = {STDIN_FILENO, POLLIN, 0};
    return poll(&p, 1, 0) > 0;
}

/* Length of the escape sequence at p (p[0] = ESC), 0 if it is incomplete. *arrow receives MC_TIO_*
 * for ESC [ A..D and ESC O A..D (with any modifier parameters), else -1. */
static size_t parse_escape(const unsigned char *p, size_t n, int *arrow)
{
    *arrow = -1;
    if (n < 2) return 0;
    if (p[1] != '[' && p[1] != 'O') return 1;   /* a lone ESC: drop it, the next byte is a key */
    size_t i = 2;
    while (i < n && p[i] >= 0x20 && p[i] <= 0x3F) i++;   /* parameters and intermediates */
    if (i == n) return 0;
    switch (p[i]) {
    case 'A': *arrow = MC_TIO_UP; break;
    case 'B': *arrow = MC_TIO_DOWN; break;
    case 'C': *arrow = MC_TIO_RIGHT; break;
    case 'D': *arrow = MC_TIO_LEFT; break;
    default: break;
    }
    return i + 1;
}

int mc_tio_read_keys(void (*on_char)(void *user, unsigned char c), void (*on_arrow)(void *user, int key), void *user)
{
    static unsigned char buf[256];
    static size_t len;
    int total = 0;
    for (;;) {
        if (len == sizeof buf) len = 0;   /* only garbage gets this long */
        ssize_t n = read(STDIN_FILENO, buf + len, sizeof buf - len);
        if (n < 0) return errno == EINTR || errno == EAGAIN ? total : -1;
        if (n == 0) {
            /* nothing waiting (VMIN=0), or the terminal hung up */
            struct pollfd p = {STDIN_FILENO, POLLIN, 0};
            return poll(&p, 1, 0) > 0 && (p.revents & (POLLHUP | POLLERR | POLLNVAL)) ? -1 : total;
        }
        len += (size_t)n;
        total += (int)n;
        size_t i = 0;
        while (i < len) {
            if (buf[i] != 0x1b) {
                on_char(user, buf[i++]);
                continue;
            }
            int arrow;
            size_t used = parse_escape(buf + i, len - i, &arrow);
            if (used == 0) break;
            if (arrow >= 0) on_arrow(user, arrow);
            i += used;
        }
        memmove(buf, buf + i, len - i);
        len -= i;
    }
}

void mc_tio_wait(int timeout_ms)
{
    struct pollfd p = {STDIN_FILENO, POLLIN, 0};
    poll(&p, 1, timeout_ms);
}
