// The entry point of a watergen generator: watergen's own, and each project's
// (watergen_add_generator compiles this file with the project's node sources, which register
// their nodes before main runs).
namespace watergen::cli {
int run(int argc, char** argv);
} // namespace watergen::cli

int main(int argc, char** argv) {
    return watergen::cli::run(argc, argv);
}
