// core::run_isolated: a crash, a hang or an exception of the isolated work is an outcome,
// never the test process's end.
#include <drape/core/errors.hpp>
#include <drape/core/isolated.hpp>

#include <catch2/catch.hpp>

#include <csignal>
#include <string>
#include <thread>

using drape::core::IsolatedOutcome;
using drape::core::run_isolated;

TEST_CASE("isolated work: its bytes back, or its exception, crash or hang as an outcome", "[core][isolated]") {
    SECTION("the bytes it returns, all of them") {
        std::string big(3'000'000, 'x');
        big[1'234'567] = '\0';
        const IsolatedOutcome o = run_isolated([&] { return big; }, 30, big.size());
        CHECK(o.kind == IsolatedOutcome::Kind::finished);
        CHECK(o.output == big);
    }
    SECTION("more bytes than allowed is a crash, not a truncated result") {
        const IsolatedOutcome o = run_isolated([] { return std::string(200'000, 'y'); }, 30, 100'000);
        CHECK(o.kind == IsolatedOutcome::Kind::crashed);
        CHECK(o.output.empty());
    }
    SECTION("its exceptions, with their messages") {
        const IsolatedOutcome a = run_isolated([]() -> std::string { throw drape::InvalidInput("field x = 3"); }, 30, 0);
        CHECK(a.kind == IsolatedOutcome::Kind::invalid_input);
        CHECK(a.message == "field x = 3");
        const IsolatedOutcome b = run_isolated([]() -> std::string { throw drape::IoError("disk gone"); }, 30, 0);
        CHECK(b.kind == IsolatedOutcome::Kind::io_error);
        CHECK(b.message == "disk gone");
    }
    SECTION("a crash: the signal") {
        const IsolatedOutcome o = run_isolated(
            []() -> std::string {
                std::raise(SIGSEGV);
                return "not reached";
            },
            30, 0);
        CHECK(o.kind == IsolatedOutcome::Kind::crashed);
        CHECK(o.signal == SIGSEGV);
        CHECK_THROWS_WITH(drape::core::throw_unless_finished(o, "cannot read 'x.h5'", "the parser", 30),
                          Catch::Contains("cannot read 'x.h5': the parser crashed") &&
                              Catch::Contains("signal 11") && Catch::Contains("this process is unharmed"));
    }
    SECTION("a hang: killed at the limit") {
        const IsolatedOutcome o = run_isolated(
            []() -> std::string {
                for (;;) std::this_thread::sleep_for(std::chrono::seconds(1));
            },
            0.5, 0);
        CHECK(o.kind == IsolatedOutcome::Kind::timed_out);
        CHECK(o.seconds >= 0.5);
        CHECK(o.seconds < 5.0);
    }
}
