/* UART0 of the ARM MPS2 boards (QEMU -M mps2-an386): a CMSDK APB UART, one receive holding register
 * and no FIFO. See uart.h. */
#include "uart.h"

#include <stdint.h>

#ifndef MC_FW_CLOCK_HZ
#define MC_FW_CLOCK_HZ 25000000u
#endif

#define UART0 0x40004000u
#define REG(off) (*(volatile uint32_t *)(UART0 + (off)))
#define UART_DATA 0x000u
#define UART_STATE 0x004u     /* bit 1: RX buffer full; bit 3: RX overrun (write 1 to clear) */
#define UART_CTRL 0x008u      /* bit 0 TX enable, bit 1 RX enable, bit 3 RX interrupt enable */
#define UART_INTCLEAR 0x00Cu  /* bit 1: the RX interrupt */
#define UART_BAUDDIV 0x010u   /* clock / baud, at least 16 */
#define STATE_RXFULL (1u << 1)
#define STATE_RXOVR (1u << 3)
#define BAUD 115200u
#define RX_IRQ 0u   /* UART0's receive interrupt on the AN385/AN386 */
#define NVIC_ISER0 (*(volatile uint32_t *)0xE000E100u)
#define NVIC_ICPR0 (*(volatile uint32_t *)0xE000E280u)

void mc_fw_uart_init(void)
{
    REG(UART_CTRL) = 0;
    REG(UART_BAUDDIV) = (MC_FW_CLOCK_HZ + BAUD / 2u) / BAUD;
    REG(UART_STATE) = STATE_RXOVR;
    REG(UART_CTRL) = 3u | (1u << 3);
    NVIC_ISER0 = 1u << RX_IRQ;   /* masked by PRIMASK: it only wakes WFI */
}

void mc_fw_uart_wait(void)
{
    /* the interrupt line low, then its pending bit cleared: a byte from now on pends it again */
    REG(UART_INTCLEAR) = 1u << 1;
    NVIC_ICPR0 = 1u << RX_IRQ;
    if (REG(UART_STATE) & STATE_RXFULL) return;
    __asm__ volatile("wfi");
}

int mc_fw_uart_getc(void)
{
    if (!(REG(UART_STATE) & STATE_RXFULL)) return -1;
    return (int)(REG(UART_DATA) & 0xFFu);
}

unsigned long mc_fw_uart_base(void) { return UART0; }
