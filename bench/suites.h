// The benchmark suites (each writes CSV files into Config::out_dir).
#pragma once

#include "bench/harness.h"

namespace asgard::bench {

// Work–precision: every scene × every code × tolerance (or step) sweep.
//   workprec.csv, references.csv
void RunWorkPrecision(const Config& cfg);
// Stiff links from ω0 = 1e2 to 1e6: Asgard against CVODE.  stiff.csv
void RunStiffSweep(const Config& cfg);
// Seed Figure 5.7 (fig57.csv), Figure 5.11 (fig511.csv), skipping idle
// subsystems and editing (skip.csv).
void RunFigure57(const Config& cfg);
void RunFigure511(const Config& cfg);
void RunSkip(const Config& cfg);
// Numerical stress suite.  stress.csv, energy.csv
void RunStress(const Config& cfg);
// Contact: piles of cubes and balls in a box, Asgard against Bullet.  contact.csv
void RunContact(const Config& cfg);
// Prints the contact suite's scene `name` (e.g. pile30, or balls100_60s)
// as a scene script, for asgard's CLI; false, with the names, when unknown.
bool PrintContactScene(const std::string& name);
// Its text, or "" when unknown.
std::string ContactSceneText(const std::string& name);
// Threads: scenes on one thread and on two, wall clock and the CPU of all
// threads, and whether the results agree bit for bit.  threads.csv
void RunThreads(const Config& cfg);
// Articulated bodies: a chain of 50 and a tree of 100 linked rods against
// MuJoCo and Bullet, chains of 10 … 50 for the cost per step per body.
//   articulated.csv, articulated_refs.csv
void RunArticulated(const Config& cfg);

}  // namespace asgard::bench
