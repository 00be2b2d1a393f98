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
# The stream receiver (make firmware-stream): UART0 is a PL011 (uart_pl011.c); SysTick runs at the
# 12.5 MHz QEMU derives from the reset RCC value. Depth 6 at 96x72: bunny00's 23,687-byte stream
# and 20,736 bytes of frame buffers leave some 16 KiB of the 64 free beside the stack (depth 7's
# stream alone is 93 KB).
lm3s6965evb.uart := pl011
lm3s6965evb.clock_hz := 12500000
lm3s6965evb.stream_depth := 6
lm3s6965evb.stream_screen := 96x72
# The stream receiver with a mesh (make firmware-stream FW_MESH=1): the model capped at 600 faces, plain
# splits, the octree at depth 3: a 21.5 KB receive buffer (the stream and the mesh arrays the reader
# fills), 7 KB of level-of-detail memory and the 20 KB of frame buffers leave some 10 KiB of the 64
# beside the stack (1,000 faces would not fit).
lm3s6965evb.stream_mesh_depth := 3
lm3s6965evb.stream_mesh_faces := 600
lm3s6965evb.stream_splits := plain
