#!/usr/bin/env bash
# A film on a Slurm cluster: a job array, task i rendering frames
# i*N .. (i+1)*N - 1 of the path into one shared directory, then one job
# after them all that fills any gap and encodes the video (the frames are
# numbered globally and a frame already there is skipped, so "merging" is
# only that last run). Submit from the repository root:
#   frames=$(( $(python3 -c 'print(int(10 * 24))') + 1 ))     # floor(duration x fps) + 1 (docs/films.md)
#   array=$(sbatch --parsable --array=0-$(( (frames + 23) / 24 - 1 )) docs/paths/slurm-film.sh)
#   sbatch --dependency=afterok:$array --wrap "docs/paths/slurm-film.sh merge"
#SBATCH --job-name=sol-film
#SBATCH --cpus-per-task=8
#SBATCH --time=01:00:00
set -euo pipefail
N=${FRAMES_PER_TASK:-24}
render=(build/release/viewer/solrender --scene lattice-balls --path docs/paths/inside-the-manifold.json --fps 24
        --width 1920 --height 1080 --spp 16 -o film/frame-%06d.png)
mkdir -p film
if [ "${1:-}" = merge ]; then
  "${render[@]}" --video film.mp4   # renders only frames a failed task left out, then encodes
else
  first=$((SLURM_ARRAY_TASK_ID * N))
  "${render[@]}" --frames "$first:$((first + N))"
fi
