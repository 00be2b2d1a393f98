# lm3s6965evb: Cortex-M3 (no FPU), 256 KiB flash, 64 KiB RAM. The default bake: depth 7 at 160x128
# (bunny00: about 86 KB of model data, 60 KiB of frame buffers).
lm3s6965evb.cpu := -mcpu=cortex-m3 -mthumb -mfloat-abi=soft
lm3s6965evb.qemu := lm3s6965evb
lm3s6965evb.depth := 7
lm3s6965evb.screen := 160x128
# The mesh bake (make firmware FW_MESH=1): 160x128's frame buffers leave no RAM for the mesh part, so
# 128x96 (36 KiB of buffers, and 1,920 bytes of sparse depth buffer bits for the lines style) and
# bunny00 capped at 2300 faces: about 9.6 bytes of RAM a face (ancestor map 2 and vertex cache 16
# bytes a vertex, the line drawings' memory) leaves some 500 bytes of the 64 KiB free beside the
# 3840-byte stack, and the flash image is about 220 KiB of the 256.
lm3s6965evb.mesh_screen := 128x96
lm3s6965evb.mesh_faces := 2300
