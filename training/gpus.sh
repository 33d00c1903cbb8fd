# Sourced by the *_gpu.sh scripts: GPUS, the number of GPUs to spread work over, from the variable
# GPUS if set, else the count nvidia-smi lists, else 1. Work item K runs on GPU K % GPUS: Vulkan
# programs with LUCID_DEVICE=#K (the loader's K-th device), PyTorch with CUDA_VISIBLE_DEVICES=K.
if [ -z "${GPUS:-}" ]; then
  GPUS=$( (nvidia-smi -L 2>/dev/null || true) | grep -c '^GPU ' || true)
  if [ "$GPUS" -lt 1 ]; then GPUS=1; fi
fi
# The environment that puts work item $1 on its GPU (nothing on a machine of one GPU).
gpu_env() {
  if [ "$GPUS" -gt 1 ]; then
    echo "LUCID_DEVICE=#$(($1 % GPUS)) CUDA_VISIBLE_DEVICES=$(($1 % GPUS))"
  fi
}
# The environment that gives work item $1 the $2 GPUs from $1 * $2 on, for a data-parallel
# training (parallel.py; the caller checks that there are that many).
gpu_set() {
  local list="" j
  for ((j = 0; j < $2; j++)); do list+="${list:+,}$(($1 * $2 + j))"; done
  echo "CUDA_VISIBLE_DEVICES=$list"
}
