// The haif subcommands; each returns the process exit status.
#pragma once

namespace haif {

int commandRun(int argc, char** argv);        ///< haif run SCENE ...
int commandCalibrate(int argc, char** argv);  ///< haif calibrate ...
int commandBench(int argc, char** argv);      ///< haif bench ...

}  // namespace haif
