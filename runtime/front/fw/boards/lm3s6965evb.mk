# lm3s6965evb: Cortex-M3 (no FPU), 256 KiB flash, 64 KiB RAM. The default bake: depth 7 at 160x128
# (bunny00: about 86 KB of model data, 60 KiB of frame buffers).
lm3s6965evb.cpu := -mcpu=cortex-m3 -mthumb -mfloat-abi=soft
lm3s6965evb.qemu := lm3s6965evb
lm3s6965evb.depth := 7
lm3s6965evb.screen := 160x128
