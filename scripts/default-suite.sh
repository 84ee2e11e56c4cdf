# The default suite's two parts as impactbench suite arguments, in one place: sourced by
# scripts/benchmark.sh (which runs them) and bench/suite_scaling.sh (which times part 1 on 1, 2, ... workers).
# duration: the forced cases' cut (benchmark.sh --full empties it).
paper_suite_args=(scenarios/paper --engines reference,mujoco,ode,bullet --laws hertz,viscoelastic,newton
                  --paths matched,injected,native --dt 1e-4,5e-5)
paper_suite_duration=(--duration 50)
search_suite_args=(scenarios/stiff scenarios/extreme --engines reference,mujoco,ode,bullet
                   --laws hertz,viscoelastic,newton --paths matched --find-steps --step-range 1e-5,1e-3 --duration 5
                   --repeat 0)
