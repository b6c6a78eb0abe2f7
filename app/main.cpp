// app/main.cpp: the wisp executable; everything happens in app/commands/cli.cpp.
#include "app/commands/cli.h"

int main(int argc, char** argv)
{
    return wisp::runCli(argc, argv);
}
