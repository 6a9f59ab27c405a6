// process.cpp: run_process (util.hpp).
#include <cerrno>
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include "model/util/util.hpp"

extern char** environ;

namespace hc::util {

int run_process(const std::vector<std::string>& argv, const ProcessOptions& opt) {
    if (argv.empty()) throw InternalError("run_process: empty command");
    // everything the child needs is built before fork(): after it, only system calls
    std::vector<char*> args;
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    std::vector<std::string> env_store;
    for (char** e = environ; *e; ++e) {
        const std::string kv(*e);
        bool overridden = false;
        for (const auto& x : opt.extra_env)
            if (kv.substr(0, kv.find('=') + 1) == x.substr(0, x.find('=') + 1)) overridden = true;
        if (!overridden) env_store.push_back(kv);
    }
    for (const auto& e : opt.extra_env) env_store.push_back(e);
    std::vector<char*> envp;
    for (auto& e : env_store) envp.push_back(e.data());
    envp.push_back(nullptr);
    const std::string cwd = opt.cwd.string(), log = opt.log.string(), out = opt.stdout_file.string();

    const pid_t pid = ::fork();
    if (pid < 0) throw SimulatorError("cannot start '" + argv[0] + "': fork failed");
    if (pid == 0) {
        if (!cwd.empty() && ::chdir(cwd.c_str()) != 0) ::_exit(126);
        const int lfd = log.empty() ? -1 : ::open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
        const int ofd = out.empty() ? lfd : ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if ((!log.empty() && lfd < 0) || (!out.empty() && ofd < 0)) ::_exit(126);
        if (ofd >= 0) ::dup2(ofd, 1);
        if (lfd >= 0) ::dup2(lfd, 2);
        ::execvpe(args[0], args.data(), envp.data());
        ::_exit(127);
    }
    int st = 0;
    while (::waitpid(pid, &st, 0) < 0)
        if (errno != EINTR) throw SimulatorError("waiting for '" + argv[0] + "' failed");
    if (WIFEXITED(st)) {
        if (WEXITSTATUS(st) == 127) throw SimulatorError("cannot start '" + argv[0] + "' (not found or not executable)");
        return WEXITSTATUS(st);
    }
    return 128 + (WIFSIGNALED(st) ? WTERMSIG(st) : 0);
}

std::string log_tail(const std::filesystem::path& p, std::size_t n) {
    std::string s;
    try {
        s = read_file(p);
    } catch (const InputError&) {
        return "(no log)";
    }
    return s.size() > n ? "..." + s.substr(s.size() - n) : s;
}

}  // namespace hc::util
