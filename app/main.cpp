// app/main.cpp: the wisp executable; everything happens in app/cli.cpp.
#include "app/cli.h"

int main(int argc, char** argv)
{
    return wisp::runCli(argc, argv);
}
