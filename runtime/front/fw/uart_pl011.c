/* UART0 of the TI Stellaris LM3S6965 (QEMU -M lm3s6965evb): an ARM PL011. See uart.h. */
#include "uart.h"

#include <stdint.h>

#ifndef MC_FW_CLOCK_HZ
#define MC_FW_CLOCK_HZ 12500000u
#endif

#define UART0 0x4000C000u
#define REG(base, off) (*(volatile uint32_t *)((base) + (off)))
#define UART_DR 0x000u
#define UART_FR 0x018u      /* flags: bit 4 RXFE, the receive FIFO is empty */
#define UART_IBRD 0x024u
#define UART_FBRD 0x028u
#define UART_LCRH 0x02Cu    /* bits 6:5 word length (3: 8 bits), bit 4 FEN (16-byte FIFOs) */
#define UART_CTL 0x030u     /* bit 0 UARTEN, bit 8 TXE, bit 9 RXE */
#define UART_IM 0x038u      /* interrupt mask: bit 4 receive, bit 6 receive timeout */
#define UART_ICR 0x044u     /* interrupt clear, the same bits */
#define RX_INTS ((1u << 4) | (1u << 6))
#define FR_RXFE (1u << 4)
/* the LM3S6965's clock gating and pin muxing: UART0 is on PA0 (RX) and PA1 (TX) */
#define SYSCTL_RCGC1 0x400FE104u   /* bit 0: UART0 */
#define SYSCTL_RCGC2 0x400FE108u   /* bit 0: GPIO port A */
#define GPIOA 0x40004000u
#define GPIO_AFSEL 0x420u
#define GPIO_DEN 0x51Cu
#define BAUD 115200u
#define RX_IRQ 5u   /* UART0's interrupt on the LM3S6965 */
#define NVIC_ISER0 (*(volatile uint32_t *)0xE000E100u)
#define NVIC_ICPR0 (*(volatile uint32_t *)0xE000E280u)

void mc_fw_uart_init(void)
{
    *(volatile uint32_t *)SYSCTL_RCGC1 |= 1u;
    *(volatile uint32_t *)SYSCTL_RCGC2 |= 1u;
    REG(GPIOA, GPIO_AFSEL) |= 3u;
    REG(GPIOA, GPIO_DEN) |= 3u;
    REG(UART0, UART_CTL) = 0;
    /* divisor = clock / (16 * baud) in Q6: IBRD its integer part, FBRD its fraction */
    const uint32_t q6 = (uint32_t)(((uint64_t)MC_FW_CLOCK_HZ * 4u + BAUD / 2u) / BAUD);
    REG(UART0, UART_IBRD) = q6 >> 6;
    REG(UART0, UART_FBRD) = q6 & 63u;
    /* written after the divisors: it latches them. FIFOs stay off (a one-byte holding register):
     * QEMU empties the receive FIFO whenever FEN changes, which would drop a byte that came before
     * this line; a FIFO would not save a paced sender anyway, since drawing a level takes far longer
     * than 16 bytes do at any baud rate */
    REG(UART0, UART_LCRH) = 3u << 5;
    REG(UART0, UART_CTL) = (1u << 0) | (1u << 8) | (1u << 9);
    REG(UART0, UART_IM) = RX_INTS;
    NVIC_ISER0 = 1u << RX_IRQ;   /* masked by PRIMASK: it only wakes WFI */
}

void mc_fw_uart_wait(void)
{
    /* the interrupt line low, then its pending bit cleared: a byte from now on pends it again */
    REG(UART0, UART_ICR) = RX_INTS;
    NVIC_ICPR0 = 1u << RX_IRQ;
    if (!(REG(UART0, UART_FR) & FR_RXFE)) return;
    __asm__ volatile("wfi");
}

int mc_fw_uart_getc(void)
{
    if (REG(UART0, UART_FR) & FR_RXFE) return -1;
    /* bits 11:8 flag a framing, parity, break or overrun error: the byte is passed on anyway, and
     * the stream's CRC-32 refuses whatever it spoiled */
    return (int)(REG(UART0, UART_DR) & 0xFFu);
}

unsigned long mc_fw_uart_base(void) { return UART0; }
