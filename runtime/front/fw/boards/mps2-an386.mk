# mps2-an386: Cortex-M4F, 4 MiB code memory, 4 MiB RAM. The default bake: depth 8 at 320x240, the
# host benchmark's settings, so instructions per point compare directly.
mps2-an386.cpu := -mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16
mps2-an386.qemu := mps2-an386
mps2-an386.depth := 8
mps2-an386.screen := 320x240
# The mesh bake (make firmware FW_MESH=1): the whole mesh at the same screen (mesh_faces 0: bunny00's
# 75408 faces, about 2.7 MB of flash and 0.9 MB of RAM with its vertex cache). Without the level's
# neighbour table (--mesh-neighbours, which would fit): under QEMU's instruction counts it made a
# level change about six times dearer (a split 840 instructions instead of 130) and saved the
# coarse line frames only 3 to 9 % (there are no cache misses to save on this core): make
# bench-firmware with the line below added, against its run without (tests/bench/RESULTS.md).
#   mps2-an386.mesh_opts := --mesh-neighbours
mps2-an386.mesh_faces := 0
# The stream receiver (make firmware-stream): UART0 is a CMSDK APB UART (uart_cmsdk.c) on the 25 MHz
# system clock. Depth 7 at 160x120 (93,051 bytes): QEMU hands this UART one byte per turn of its
# main loop, some 20-40 KB/s, so depth 8's 369 KB (FW_STREAM_DEPTH=8) takes several times longer.
mps2-an386.uart := cmsdk
mps2-an386.clock_hz := 25000000
mps2-an386.stream_depth := 7
mps2-an386.stream_screen := 160x120
# The stream receiver with a mesh (make firmware-stream FW_MESH=1): the model capped at 4,000 faces,
# packed splits (stream version 3: the reader keeps the level's mesh while it decodes), the octree at
# depth 3: a short stream for this slow UART.
mps2-an386.stream_mesh_depth := 3
mps2-an386.stream_mesh_faces := 4000
mps2-an386.stream_splits := packed
