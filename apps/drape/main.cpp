// drape: command-line front end of the Drape libraries.
#include "commands.hpp"
#include "interrupt.hpp"

#include <drape/core/errors.hpp>

#include <CLI/CLI.hpp>

#include <exception>
#include <iostream>

int main(int argc, char** argv) {
    CLI::App app{"drape: recover bodies and garments from a single photograph"};
    app.require_subcommand(1);
    app.set_version_flag("--version", "drape 0.1.0");
    drape::app::add_body_command(app);
    drape::app::add_fit_body_command(app);
    drape::app::add_bench_cloth_command(app);
    drape::app::add_bench_sizing_drape_command(app);
    drape::app::add_render_command(app);
    drape::app::add_segment_command(app);
    drape::app::add_strokes_command(app);
    drape::app::add_eval_segment_command(app);
    drape::app::add_pattern_command(app);
    drape::app::add_dress_command(app);
    drape::app::add_eval_dress_command(app);
    drape::app::add_synth_command(app);
    drape::app::add_recover_command(app);
    drape::app::add_eval_recover_commands(app);
    drape::app::add_animate_command(app);
    drape::app::add_tryon_commands(app);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    } catch (const drape::app::CommandExit& e) {
        if (!e.message.empty()) std::cerr << "drape: " << e.message << "\n";
        return e.code;
    } catch (const drape::InvalidInput& e) {
        std::cerr << "drape: invalid input: " << e.what() << "\n";
        return 2;
    } catch (const drape::IoError& e) {
        std::cerr << "drape: I/O error: " << e.what() << "\n";
        return 3;
    } catch (const std::exception& e) {
        std::cerr << "drape: error: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
