// The corpus sweep's worker processes: rows travel as lines of JSON and back unchanged; stand-in
// workers (a shell that prints the rows it is given) crash, fail, lie and stop short, and the sweep
// says so or recovers as its contract states. The real workers (crtforge itself) give the same
// report as one process: retroarch_corpus_test.cpp.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>

#include "crtforge/runtime/gpu_watchdog.hpp"
#include "crtforge/validate/corpus_workers.hpp"

using namespace crtforge;

namespace {

CorpusRequest request_of(const std::vector<std::string>& presets) {
    CorpusRequest request;
    request.root = "/library";
    request.presets = presets;
    request.targets = {TargetId::Spirv, TargetId::Wgsl};
    return request;
}

// A row with values in every field, so a field lost on the way shows.
CorpusRow full_row(const CorpusRequest& request, const std::string& preset) {
    CorpusRow row = corpus_row_for(request, preset);
    row.passes = 7;
    row.passes_spirv = 6;
    row.spirv_error = "pass 6: 'x' : undeclared identifier";
    row.warnings = 2;
    row.targets["spirv"] = {"agrees", 6, std::numeric_limits<double>::infinity(), ""};
    row.targets["wgsl"] = {"differs", 6, 31.25, "a \"quoted\" reason\twith a tab and \xc3\xa9"};
    row.retroarch = "agrees";
    row.retroarch_psnr = 48.123456789012345;
    return row;
}

// Workers that are `sh -c SCRIPT`: each argument after the script is a line to print on the rows
// descriptor, or a word telling the shell what to do instead.
const char* kScript = R"(fd=$1; shift
for a in "$@"; do
  case "$a" in
    CRASH) kill -SEGV $$ ;;
    FAIL) exit 2 ;;
    GPUSTOP) exit 3 ;;
    STOP) exit 0 ;;
    HANG) exec sleep 1000 ;;
    TELL*) mkdir "$TMPDIR/left-behind" && printf '%s' "$TMPDIR" > "${a#TELL}" ;;
    *) printf '%s\n' "$a" >&"$fd" ;;
  esac
done)";

CorpusWorkers shell_workers(size_t per, std::function<std::string(const std::string&)> line_for) {
    CorpusWorkers w;
    w.executable = "/bin/sh";
    w.presets_per_process = per;
    w.arguments = [line_for](const std::vector<std::string>& presets, int fd) {
        std::vector<std::string> args{"-c", kScript, "worker", std::to_string(fd)};
        for (const std::string& p : presets) args.push_back(line_for(p));
        return args;
    };
    return w;
}

}  // namespace

TEST_CASE("a corpus row goes through its line of JSON and back unchanged", "[corpus-workers]") {
    const CorpusRequest request = request_of({"crt/a.slangp"});
    const CorpusRow row = full_row(request, "crt/a.slangp");
    const std::string line = corpus_row_line(row);
    CHECK(line.find('\n') == std::string::npos);
    auto back = corpus_row_from_line(line);
    REQUIRE(back.ok());
    CHECK(corpus_row_line(back.value()) == line);
    CHECK(back.value().targets.at("spirv").psnr == std::numeric_limits<double>::infinity());
    CHECK(back.value().targets.at("wgsl").reason == row.targets.at("wgsl").reason);
    CHECK(back.value().retroarch_psnr == row.retroarch_psnr);
    CHECK(back.value().folder == "crt");

    for (const char* bad : {"", "[]", "{\"preset\": 1}", "{\"preset\": \"a\"", "not json"}) {
        INFO(bad);
        auto parsed = corpus_row_from_line(bad);
        REQUIRE_FALSE(parsed.ok());
        CHECK_THAT(parsed.error().str(), Catch::Matchers::Contains("corpus row is malformed"));
    }
    std::string no_status = line;
    no_status.replace(no_status.find("\"status\""), 8, "\"state\"");
    CHECK_FALSE(corpus_row_from_line(no_status).ok());
}

TEST_CASE("the sweep puts each worker's rows in report order and isolates a preset that kills its worker", "[corpus-workers]") {
    const std::vector<std::string> presets{"a/1.slangp", "a/2.slangp", "b/3.slangp", "b/4.slangp", "c/5.slangp", "c/6.slangp", "c/7.slangp"};
    CorpusRequest request = request_of(presets);
    // With two threads a worker's last preset overlaps the next worker's start: two run at once.
    request.jobs = GENERATE(1u, 2u);
    INFO("jobs " << request.jobs);
    // Rows come back in an order of the worker's choosing (last first here): the report's is the request's.
    size_t calls = 0, last_done = 0;
    auto progress = [&](size_t done, size_t total, const CorpusRow&) {
        ++calls;
        last_done = done;
        CHECK(total == presets.size());
    };
    SECTION("every worker ends well: the rows are the workers' rows, in order") {
        auto run = run_corpus_in_workers(request, shell_workers(3, [&](const std::string& p) { return corpus_row_line(full_row(request, p)); }),
                                         progress);
        REQUIRE(run.ok());
        REQUIRE(run.value().rows.size() == presets.size());
        for (size_t i = 0; i < presets.size(); ++i) CHECK(corpus_row_line(run.value().rows[i]) == corpus_row_line(full_row(request, presets[i])));
        CHECK(calls == presets.size());
        CHECK(last_done == presets.size());
        CHECK(run.value().total_presets == presets.size());
        CHECK(run.value().targets == std::vector<std::string>{"spirv", "wgsl"});
    }
    SECTION("a preset that crashes its worker, alone or among others, gets a crashed row; the rest are run again") {
        auto line = [&](const std::string& p) { return p == "b/3.slangp" ? std::string("CRASH") : corpus_row_line(full_row(request, p)); };
        auto run = run_corpus_in_workers(request, shell_workers(3, line), progress);
        REQUIRE(run.ok());
        const auto& rows = run.value().rows;
        REQUIRE(rows.size() == presets.size());
        for (size_t i = 0; i < presets.size(); ++i) {
            INFO(presets[i]);
            CHECK(rows[i].preset == presets[i]);
            if (presets[i] == "b/3.slangp") {
                for (const char* t : {"spirv", "wgsl"}) {
                    CHECK(rows[i].targets.at(t).status == "crashed");
                    CHECK_THAT(rows[i].targets.at(t).reason, Catch::Matchers::Contains("signal 11"));
                }
                CHECK(rows[i].folder == "b");
            } else {
                CHECK(corpus_row_line(rows[i]) == corpus_row_line(full_row(request, presets[i])));
            }
        }
        CHECK(calls == presets.size());
    }
    SECTION("what a crashed worker leaves in its temporary folder goes with the sweep's") {
        const std::string told = std::string(std::getenv("TMPDIR") ? std::getenv("TMPDIR") : "/tmp") + "/crtforge-workers-test-" +
                                 std::to_string(::getpid());
        auto line = [&](const std::string& p) {
            if (p == "a/1.slangp") return "TELL" + told;  // then its row: a TELL is not a row
            return p == "a/2.slangp" ? std::string("CRASH") : corpus_row_line(full_row(request, p));
        };
        CorpusWorkers w = shell_workers(3, line);
        const auto base = w.arguments;
        w.arguments = [&, base](const std::vector<std::string>& names, int fd) {
            auto args = base(names, fd);
            if (names.front() == "a/1.slangp") args.insert(args.begin() + 5, corpus_row_line(full_row(request, "a/1.slangp")));
            return args;
        };
        auto run = run_corpus_in_workers(request, w);
        REQUIRE(run.ok());
        std::ifstream in(told);
        const std::string folder((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        std::remove(told.c_str());
        REQUIRE_FALSE(folder.empty());
        CHECK_FALSE(std::filesystem::exists(folder));
        CHECK(run.value().rows[1].targets.at("spirv").status == "crashed");
    }
    // `stopped`'s worker does `word`; its row is a timeout saying `why`, every other row the worker's.
    auto expect_timeout_row = [&](const std::string& stopped, const std::string& word, double preset_timeout, const std::string& why) {
        auto line = [&](const std::string& p) { return p == stopped ? word : corpus_row_line(full_row(request, p)); };
        CorpusWorkers w = shell_workers(3, line);
        w.preset_timeout_s = preset_timeout;
        auto run = run_corpus_in_workers(request, w, progress);
        REQUIRE(run.ok());
        const auto& rows = run.value().rows;
        REQUIRE(rows.size() == presets.size());
        for (size_t i = 0; i < presets.size(); ++i) {
            INFO(presets[i]);
            if (presets[i] == stopped) {
                CHECK(rows[i].targets.at("spirv").status == "timeout");
                CHECK_THAT(rows[i].targets.at("wgsl").reason, Catch::Matchers::Contains(why));
            } else {
                CHECK(corpus_row_line(rows[i]) == corpus_row_line(full_row(request, presets[i])));
            }
        }
        CHECK(calls == presets.size());
    };
    SECTION("a preset that never ends is stopped after the time limit and gets a timeout row; the rest are run again") {
        expect_timeout_row("c/6.slangp", "HANG", 0.5, "no result within 0.5 s (--preset-timeout)");
    }
    SECTION("a worker stopped by --gpu-timeout (exit code 3) gives its preset a timeout row; the rest are run again") {
        static_assert(kExitGpuTimeout == 3);
        expect_timeout_row("b/4.slangp", "GPUSTOP", 0, "(--gpu-timeout): stopped");
    }
    SECTION("a shard runs only its presets") {
        CorpusRequest shard = request;
        shard.shard = Shard{2, 3};
        auto run = run_corpus_in_workers(shard, shell_workers(1, [&](const std::string& p) { return corpus_row_line(full_row(request, p)); }));
        REQUIRE(run.ok());
        REQUIRE(run.value().rows.size() == 2);
        CHECK(run.value().rows[0].preset == "a/2.slangp");
        CHECK(run.value().rows[1].preset == "c/5.slangp");
        CHECK(run.value().shard_index == 2);
    }
}

TEST_CASE("a worker that fails, stops short, writes a foreign or malformed row ends the sweep with one line", "[corpus-workers]") {
    const std::vector<std::string> presets{"a/1.slangp", "a/2.slangp", "a/3.slangp"};
    const CorpusRequest request = request_of(presets);
    auto good = [&](const std::string& p) { return corpus_row_line(full_row(request, p)); };
    auto expect_error = [&](std::function<std::string(const std::string&)> line, const std::string& wanted) {
        auto run = run_corpus_in_workers(request, shell_workers(2, line));
        REQUIRE_FALSE(run.ok());
        const std::string message = run.error().str();
        CHECK_THAT(message, Catch::Matchers::Contains(wanted));
        CHECK(message.find('\n') == std::string::npos);
    };
    expect_error([&](const std::string& p) { return p == "a/2.slangp" ? std::string("FAIL") : good(p); }, "exit code 2");
    expect_error([&](const std::string& p) { return p == "a/2.slangp" ? std::string("STOP") : good(p); }, "without a row for 'a/2.slangp'");
    expect_error([&](const std::string& p) { return p == "a/2.slangp" ? good("z/9.slangp") : good(p); }, "not one of its presets");
    expect_error([&](const std::string& p) { return p == "a/2.slangp" ? good("a/1.slangp") : good(p); }, "not one of its presets");
    expect_error([&](const std::string& p) { return p == "a/2.slangp" ? std::string("{\"preset\": ") : good(p); }, "malformed");

    CorpusWorkers missing = shell_workers(2, good);
    missing.executable = "/nonexistent/crtforge";
    auto run = run_corpus_in_workers(request, missing);
    REQUIRE_FALSE(run.ok());
    CHECK_THAT(run.error().str(), Catch::Matchers::Contains("/nonexistent/crtforge"));
}
