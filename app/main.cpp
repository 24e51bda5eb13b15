// Avenues — the `avenues` executable: the command line and nothing more (app/cli.h).
#include "app/cli.h"

int main(int argc, char** argv) { return avenues::app::run_cli(argc, argv); }
