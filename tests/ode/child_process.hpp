// Running a piece of a test in a child process: for what ends the process (ODE's dError aborts).
#pragma once

#include <catch2/catch.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <string>
#include <utility>

namespace gdc::ode::test {

/// Runs `body` in a child process with stderr captured; returns (exit status, stderr text).
template <class Body>
std::pair<int, std::string> runInChild(Body body) {
    int pipeEnds[2];
    REQUIRE(pipe(pipeEnds) == 0);
    std::fflush(nullptr);
    const pid_t child = fork();
    REQUIRE(child >= 0);
    if (child == 0) {
        dup2(pipeEnds[1], 2);
        close(pipeEnds[0]);
        body();
        _exit(0);
    }
    close(pipeEnds[1]);
    std::string text;
    char buffer[512];
    for (ssize_t n; (n = read(pipeEnds[0], buffer, sizeof buffer)) > 0;) text.append(buffer, static_cast<std::size_t>(n));
    close(pipeEnds[0]);
    int status = 0;
    waitpid(child, &status, 0);
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, text};
}

}  // namespace gdc::ode::test
