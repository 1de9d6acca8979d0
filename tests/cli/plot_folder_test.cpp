// The folder a plot is drawn in, attacked by another local user. The user `nobody` shares a sticky,
// world-writable TMPDIR with us, as every user shares /tmp. Before the plots it pre-creates the folder names a
// predictable scheme would use (radchain-plot-<pid>-<n> for the next few thousand pids), each holding gnuplot.log
// as a link to one of our files; while the plots run it watches TMPDIR and tries to plant a link and a script in
// every folder that appears. Our file must stay whole, nothing must be planted, and the plots must succeed.
#include "cli_helpers.hpp"

#include <fcntl.h>
#include <grp.h>
#include <poll.h>
#include <pwd.h>
#include <sys/inotify.h>
#include <sys/stat.h>

#include <cstdio>
#include <cstring>

#include <gtest/gtest.h>

namespace {
using namespace radchain::test;

struct AttackerReport {
  int folders_seen = 0;  // folders that appeared in TMPDIR while the plots ran
  int plants = 0;        // links or files the attacker managed to create inside one of them
};

long last_pid() {
  std::ifstream in("/proc/sys/kernel/ns_last_pid");
  long pid = 0;
  in >> pid;
  return pid;
}

// Runs as `nobody` in a child process: pre-creates the predictable folders, signals `ready`, then attacks every
// folder that appears until `stop` is closed, and writes its report to `report`.
[[noreturn]] void attack(const passwd& nobody, const fs::path& shared_tmp, const fs::path& victim, int ready, int stop,
                         int report, std::initializer_list<int> parents_ends) {
  for (int fd : parents_ends) ::close(fd);  // so that the parent's close of `stop` ends the poll below
  if (::setgroups(0, nullptr) != 0 || ::setgid(nobody.pw_gid) != 0 || ::setuid(nobody.pw_uid) != 0) ::_exit(10);
  const long first = last_pid();
  for (long pid = first; pid < first + 3000; ++pid)
    for (int n = 0; n < 2; ++n) {
      const fs::path folder = shared_tmp / ("radchain-plot-" + std::to_string(pid) + "-" + std::to_string(n));
      if (::mkdir(folder.c_str(), 0777) != 0) continue;
      ::chmod(folder.c_str(), 0777);
      [[maybe_unused]] int ignored = ::symlink(victim.c_str(), (folder / "gnuplot.log").c_str());
    }
  const int watch = ::inotify_init1(IN_CLOEXEC);
  if (watch < 0 || ::inotify_add_watch(watch, shared_tmp.c_str(), IN_CREATE) < 0) ::_exit(11);
  [[maybe_unused]] ssize_t ignored = ::write(ready, "r", 1);
  AttackerReport result;
  alignas(inotify_event) char events[8192];
  for (;;) {
    pollfd fds[2] = {{watch, POLLIN, 0}, {stop, POLLIN, 0}};
    if (::poll(fds, 2, 20000) <= 0 || (fds[1].revents & (POLLIN | POLLHUP))) break;
    const ssize_t length = ::read(watch, events, sizeof events);
    for (ssize_t at = 0; at < length;) {
      const auto* event = reinterpret_cast<const inotify_event*>(events + at);
      at += static_cast<ssize_t>(sizeof(inotify_event) + event->len);
      if (!(event->mask & IN_ISDIR)) continue;
      ++result.folders_seen;
      const fs::path folder = shared_tmp / event->name;
      if (::symlink(victim.c_str(), (folder / "gnuplot.log").c_str()) == 0) ++result.plants;
      const int script = ::open((folder / "plot-png.gp").c_str(), O_WRONLY | O_CREAT | O_EXCL, 0666);
      if (script >= 0) {
        ++result.plants;
        ::close(script);
      }
    }
  }
  ignored = ::write(report, &result, sizeof result);
  ::_exit(0);
}

TEST(PlotFolder, AnotherLocalUserCannotPlantLinksOrScripts) {
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) GTEST_SKIP() << "gnuplot is not installed";
  const passwd* nobody = ::getpwnam("nobody");
  // CI runs as root, which is what lets this test become a second user.
  if (::geteuid() != 0 || nobody == nullptr) GTEST_SKIP() << "needs root and the user nobody to play another user";
  Scratch scratch;
  const fs::path shared_tmp = scratch / "tmp";
  fs::create_directories(shared_tmp);
  fs::permissions(shared_tmp, fs::perms::all | fs::perms::sticky_bit);
  const fs::path victim = scratch / "victim.txt";
  write_text(victim, "the victim's data\n");

  int ready[2], stop[2], report[2];
  // Close-on-exec: the radchain processes started below must not hold the attacker's `stop` pipe open.
  ASSERT_EQ(::pipe2(ready, O_CLOEXEC), 0);
  ASSERT_EQ(::pipe2(stop, O_CLOEXEC), 0);
  ASSERT_EQ(::pipe2(report, O_CLOEXEC), 0);
  const pid_t attacker = ::fork();
  ASSERT_GE(attacker, 0);
  if (attacker == 0) attack(*nobody, shared_tmp, victim, ready[1], stop[0], report[1], {ready[0], stop[1], report[0]});
  ::close(ready[1]);
  ::close(stop[0]);
  ::close(report[1]);
  char byte = 0;
  ASSERT_EQ(::read(ready[0], &byte, 1), 1) << "the attacker could not start";

  ::setenv("TMPDIR", shared_tmp.c_str(), 1);
  std::vector<CliResult> runs;
  for (int k = 0; k < 3; ++k)
    runs.push_back(run_cli(scratch, "sweep '" + sbv_file + "' --set 'optics.aperture=15 cm:30 cm:4' --out /dev/null --plot '" +
                                        (scratch / ("p" + std::to_string(k) + ".png")).string() + "'"));
  ::unsetenv("TMPDIR");
  ::close(stop[1]);
  AttackerReport result;
  ASSERT_EQ(::read(report[0], &result, sizeof result), static_cast<ssize_t>(sizeof result));
  int status = 0;
  ::waitpid(attacker, &status, 0);

  for (std::size_t k = 0; k < runs.size(); ++k) {
    EXPECT_EQ(runs[k].exit_code, 0) << runs[k].err;
    EXPECT_EQ(read_text(scratch / ("p" + std::to_string(k) + ".png")).substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  }
  EXPECT_EQ(read_text(victim), "the victim's data\n") << "a planted link made radchain truncate another file";
  EXPECT_GE(result.folders_seen, 3) << "the attacker never saw the plot folders: the test did not exercise the race";
  EXPECT_EQ(result.plants, 0) << "another user could write into radchain's plot folder";
  // Each plot removes its folder: only the attacker's decoys are left.
  for (const auto& entry : fs::directory_iterator(shared_tmp)) {
    struct stat st {};
    ASSERT_EQ(::lstat(entry.path().c_str(), &st), 0);
    EXPECT_EQ(st.st_uid, nobody->pw_uid) << entry.path() << " was left behind by radchain";
  }
}

}  // namespace
