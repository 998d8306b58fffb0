// sim/cli: agv-sim's command line: every option, -h/--help and --version, and refusals that
// name the option.
#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

extern "C" {
#include "sim/cli.h"
}

namespace
{

struct Parsed {
    int rc;
    sim_cli_t cli;
    std::string out, err;
    std::shared_ptr<std::vector<std::string>> args; // cli points into these
};

Parsed parse(std::vector<std::string> list)
{
    auto args = std::make_shared<std::vector<std::string>>(std::move(list));
    args->insert(args->begin(), "agv-sim");
    std::vector<char *> argv;
    for (auto &a : *args)
        argv.push_back(a.data());
    argv.push_back(nullptr);
    char *ob = nullptr, *eb = nullptr;
    size_t on = 0, en = 0;
    FILE *o = open_memstream(&ob, &on), *e = open_memstream(&eb, &en);
    Parsed p;
    p.args = args;
    p.rc = sim_cli_parse((int)args->size(), argv.data(), &p.cli, o, e);
    fclose(o);
    fclose(e);
    p.out = ob;
    p.err = eb;
    free(ob);
    free(eb);
    return p;
}

TEST(Cli, EveryOption)
{
    Parsed p = parse({"--scenario", "s.json", "--seed", "12", "--report", "r.json", "--log-dir",
                      "a/b", "--lcm", "udpm://x", "--quiet", "--trace", "--stats"});
    ASSERT_EQ(p.rc, -1) << p.err;
    EXPECT_STREQ(p.cli.scenario, "s.json");
    EXPECT_EQ(p.cli.seed, 12);
    EXPECT_STREQ(p.cli.report, "r.json");
    EXPECT_STREQ(p.cli.log_dir, "a/b");
    EXPECT_STREQ(p.cli.lcm_url, "udpm://x");
    EXPECT_EQ(p.cli.quiet + p.cli.trace + p.cli.stats, 3);
    p = parse({"--scenario=s.json"});
    ASSERT_EQ(p.rc, -1);
    EXPECT_EQ(p.cli.seed, -1);
    EXPECT_EQ(p.cli.report, nullptr);
    EXPECT_EQ(p.cli.realtime, 0.0); // not paced unless asked
}

TEST(Cli, RealtimeTakesAnOptionalFactor)
{
    Parsed p = parse({"--scenario", "s", "--realtime"});
    ASSERT_EQ(p.rc, -1) << p.err;
    EXPECT_EQ(p.cli.realtime, 1.0);
    p = parse({"--scenario", "s", "--realtime=10"});
    ASSERT_EQ(p.rc, -1) << p.err;
    EXPECT_EQ(p.cli.realtime, 10.0);
    p = parse({"--scenario", "s", "--realtime=0.5"});
    ASSERT_EQ(p.rc, -1) << p.err;
    EXPECT_EQ(p.cli.realtime, 0.5);
}

TEST(Cli, HelpAndVersionGoToStdoutAndExitZero)
{
    for (const char *h : {"-h", "--help"}) {
        Parsed p = parse({h});
        EXPECT_EQ(p.rc, 0);
        EXPECT_NE(p.out.find("usage: agv-sim --scenario FILE"), std::string::npos);
        EXPECT_NE(p.out.find("docs/interfaces.md"), std::string::npos);
        EXPECT_EQ(p.out.find("CONTRACT"), std::string::npos); // only the repository is named
        EXPECT_EQ(p.out.find("../"), std::string::npos);
    }
    Parsed p = parse({"--version"});
    EXPECT_EQ(p.rc, 0);
    EXPECT_EQ(p.out, "agv-sim " CY_VERSION "\n");
}

TEST(Cli, BadCommandLinesNameTheOption)
{
    struct {
        std::vector<std::string> args;
        const char *message;
    } cases[] = {
        {{}, "--scenario is required"},
        {{"--scenario", "s", "--seed", "x"}, "--seed: \"x\" is not a non-negative integer"},
        {{"--scenario", "s", "--seed", "-3"}, "--seed: \"-3\""},
        {{"--scenario", "s", "--seed", ""}, "--seed: \"\""},
        {{"--scenario", "s", "extra"}, "unexpected argument \"extra\""},
        {{"--scenario", "s", "--frobnicate"}, "unknown option \"--frobnicate\""},
        {{"--scenario"}, "--scenario needs a value"},
        {{"--scenario", "s", "--realtime=0"}, "--realtime: \"0\" is not a factor above 0"},
        {{"--scenario", "s", "--realtime=-2"}, "--realtime: \"-2\""},
        {{"--scenario", "s", "--realtime=fast"}, "--realtime: \"fast\""},
        {{"--scenario", "s", "--realtime=nan"}, "--realtime: \"nan\""},
        {{"--scenario", "s", "--realtime=1e7"}, "--realtime: \"1e7\""},
        {{"--scenario", "s", "--realtime", "10"},
         "--realtime takes its factor after '=': "
         "--realtime=10"},
    };
    for (auto &c : cases) {
        Parsed p = parse(c.args);
        EXPECT_EQ(p.rc, 2) << c.message;
        EXPECT_NE(p.err.find(c.message), std::string::npos) << p.err;
    }
}

} // namespace
