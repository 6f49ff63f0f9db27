#!/ usr / bin / env bash
#The main demo(release preset) : the humanoid walks in MuJoCo.The closed loop of thesis figure
# 6.1(NMPC->interpolation->Ceres IK->MuJoCo, CoM feedback, ZMP from the ankle sensors)
#runs the four test tasks of thesis §9.2 against a target object(examples / walking_simulation
#-- video) : straight 2 m, curved walk to a target on the left, a chair on the way, and the
#environmental scan(target behind the robot).Then the six HRP - 2 pattern scenarios of §9.1
#(examples / walking_scenarios) and the walking QP sequence(examples / qp_walking_sequence).
#Extra arguments go to walking_simulation, e.g.task names or --no - plot.
#bash scripts / demo.sh[straight | curved | obstacle | scan...][--no - plot]
set - euo pipefail cd "$(dirname " $ { BASH_SOURCE[0] }
")/.." root =
    "$(pwd)"

    bash scripts /
    setup.sh cmake-- preset release cmake-- build-- preset release-- target walking_simulation
        walking_scenarios qp_walking_sequence

            out = "${root}/build/release/example_output" sim =
        "${out}/simulation" mkdir -
            p "${sim}" echo
              "demo: running build/release/examples/walking_simulation --video --out ${sim} $*"
              "${root}/build/release/examples/walking_simulation" --video-- out
            "${sim}"
            "$@" echo
            "demo: running build/release/examples/walking_scenarios all --out ${out}"
            "${root}/build/release/examples/walking_scenarios" all-- out
            "${out}" echo
            "demo: running build/release/examples/qp_walking_sequence --quiet (in ${out})"(
                cd "${out}" && "${root}/build/release/examples/qp_walking_sequence" --quiet)

                echo "demo: the walk in MuJoCo (CSV, PNG, MP4) is in ${sim}:" ls -
            1 "${sim}" |
        grep - v '_frames$' echo
            "demo: per task: ${sim}/<task>.png (path, desired vs measured ZMP, velocity "
            "histograms)," echo
            "      ${sim}/<task>_frames.png (frame strip), ${sim}/<task>.mp4 (video, 8x real "
            "time)," echo
            "      ${sim}/simulation_summary.csv (reached, distance, ZMP statistics per task)" echo
            "demo: the pattern generator's plots are ${out}/*.png"
