#include <strata/core/child_process.h>

#include <fcntl.h>
#include <poll.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace strata {

namespace {

int g_child_fd = -1;  // in a child of run_in_child: the pipe's writing end; -1 elsewhere

bool write_all(int fd, const char* p, std::size_t n) {
    while (n > 0) {
        const ssize_t w = ::write(fd, p, n);
        if (w < 0 && errno == EINTR) continue;
        if (w <= 0) return false;
        p += w;
        n -= static_cast<std::size_t>(w);
    }
    return true;
}

}  // namespace

void child_exit(const std::vector<char>& bytes, int status) {
    if (g_child_fd < 0) return;
    const bool sent = write_all(g_child_fd, bytes.data(), bytes.size());
    ::_exit(sent ? status : 1);
}

ChildResult run_in_child(const std::function<void(std::vector<char>&)>& body, const Progress* progress,
                         const ChildOptions& options) {
    ChildResult result;
    int fds[2];
    if (::pipe2(fds, O_CLOEXEC) != 0) return result;
#ifdef _OPENMP
    if (options.free_openmp_threads) omp_pause_resource_all(omp_pause_hard);
#endif
    std::fflush(nullptr);  // nothing buffered twice
    const pid_t parent = ::getpid();
    const pid_t pid = ::fork();
    if (pid < 0) {
        ::close(fds[0]);
        ::close(fds[1]);
        return result;
    }
    if (pid == 0) {  // the child: run, send, leave without unwinding or atexit handlers
        ::close(fds[0]);
        // Ends with this process (the CLI's --timeout ends it while the child runs).
        if (::prctl(PR_SET_PDEATHSIG, SIGKILL) != 0 || ::getppid() != parent) ::_exit(1);
        // A crash must end the child by its signal, which the parent names (not a handler
        // the program installed, such as the CLI's, which would exit with a status instead).
        for (const int sig : {SIGSEGV, SIGBUS, SIGFPE, SIGILL}) std::signal(sig, SIG_DFL);
        g_child_fd = fds[1];
        std::vector<char> bytes;
        try {
            body(bytes);
        } catch (...) {
            ::_exit(1);
        }
        child_exit(bytes, 0);
        ::_exit(1);  // not reached
    }
    result.forked = true;
    ::close(fds[1]);
    if (progress != nullptr) progress->watch_child(static_cast<int>(pid));
    // Read until the child closes its end, asking \p progress every 0.1 s whether to stop:
    // then the child is killed (the work in it cannot be asked).
    char chunk[1 << 16];
    bool cancelled = false;
    for (;;) {
        pollfd p{fds[0], POLLIN, 0};
        const int ready = ::poll(&p, 1, 100);
        if (ready < 0 && errno != EINTR) break;
        if (progress != nullptr && progress->cancelled()) {
            cancelled = true;
            ::kill(pid, SIGKILL);
            break;
        }
        if (ready <= 0) continue;
        const ssize_t r = ::read(fds[0], chunk, sizeof chunk);
        if (r < 0 && errno == EINTR) continue;
        if (r <= 0) break;
        result.sent.insert(result.sent.end(), chunk, chunk + r);
    }
    ::close(fds[0]);
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    if (cancelled) throw Cancelled();
    if (WIFSIGNALED(status)) result.signal = WTERMSIG(status);
    if (WIFEXITED(status)) result.exit_status = WEXITSTATUS(status);
    return result;
}

}  // namespace strata
