/* Polled UART receive for the stream firmware (stream_main.c): one driver per board, chosen by
 * boards/B.mk's B.uart: uart_pl011.c (the LM3S6965's UART0, a PL011 with Stellaris clock gating)
 * and uart_cmsdk.c (the MPS2's CMSDK APB UART0).
 *
 * Promise: mc_fw_uart_init enables UART0's receiver at 115200 baud 8N1 from the board's clock
 * (MC_FW_CLOCK_HZ) and its receive interrupt in the NVIC; mc_fw_uart_getc returns the next
 * received byte, or -1 when none is waiting, and never blocks; mc_fw_uart_wait sleeps (WFI) until a
 * byte comes or another event wakes the core. The caller keeps interrupts masked (PRIMASK): none is
 * ever taken, a pending one only ends WFI, so no handler and no vector is needed. Under QEMU the
 * baud rate means nothing: its serial backend hands the UART a byte only when the receive FIFO (or
 * holding register) has room, so nothing is lost however late the bytes are read.
 */
#ifndef MODELC_FW_UART_H
#define MODELC_FW_UART_H

void mc_fw_uart_init(void);
int mc_fw_uart_getc(void);
void mc_fw_uart_wait(void);
/* UART0's base address, for the banner */
unsigned long mc_fw_uart_base(void);

#endif
