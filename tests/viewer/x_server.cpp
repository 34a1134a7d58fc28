#include "x_server.hpp"

#include <cerrno>
#include <csignal>
#include <fcntl.h>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <poll.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace gdc::viewer::test {
namespace {

class Xvfb {
public:
    Xvfb() { error_ = start(); }
    ~Xvfb() {
        if (pid_ > 0) {
            kill(pid_, SIGTERM);
            waitpid(pid_, nullptr, 0);
        }
    }
    const std::string& error() const { return error_; }

private:
    std::string start() {
        int fds[2];
        if (pipe(fds) != 0) return std::string("pipe: ") + std::strerror(errno);
        // -displayfd: Xvfb picks a free display number and writes it to the pipe once it accepts
        // connections, so parallel tests never race for ":99".
        const std::string fd = std::to_string(fds[1]);
        const char* argv[] = {"Xvfb", "-displayfd", fd.c_str(), "-screen", "0", "1280x800x24",
                              "-nolisten", "tcp", "-noreset", nullptr};
        posix_spawn_file_actions_t actions;
        posix_spawn_file_actions_init(&actions);
        posix_spawn_file_actions_addclose(&actions, fds[0]);
        posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
        posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
        const int spawned = posix_spawnp(&pid_, "Xvfb", &actions, nullptr, const_cast<char**>(argv), environ);
        posix_spawn_file_actions_destroy(&actions);
        close(fds[1]);
        if (spawned != 0) {
            close(fds[0]);
            pid_ = -1;
            return std::string("cannot run Xvfb (install the xvfb package): ") + std::strerror(spawned);
        }
        std::string number;
        pollfd wait{fds[0], POLLIN, 0};
        char c = 0;
        while (poll(&wait, 1, 20000) > 0 && read(fds[0], &c, 1) == 1 && c != '\n') number += c;
        close(fds[0]);
        if (number.empty()) return "Xvfb started but reported no display within 20 s";
        setenv("DISPLAY", (":" + number).c_str(), 1);
        return {};
    }

    pid_t pid_ = -1;
    std::string error_;
};

}  // namespace

std::string ensureXServer() {
    static Xvfb server;
    if (server.error().empty()) return {};
    if (const char* display = std::getenv("DISPLAY"); display && *display) return {};
    return server.error();
}

void reportSkipped(const std::string& reason) {
    std::cout << "SKIPPED: no X server: " << reason << std::endl;
}

}  // namespace gdc::viewer::test
