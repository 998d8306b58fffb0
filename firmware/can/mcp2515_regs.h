/*
 * mcp2515_regs.h - the MCP2515's SPI instructions, register addresses and bits the driver
 * uses (DS20001801: Table 12-1 instructions, Table 11-1 register map, the register
 * descriptions of sections 3-7 and 10). Private to firmware/can.
 */
#ifndef MCP2515_REGS_H
#define MCP2515_REGS_H

/* SPI instructions */
#define MCP_RESET       0xC0u
#define MCP_READ        0x03u
#define MCP_READ_RXB(n) (0x90u | ((uint8_t)(n) << 2)) /* n = 0, 1: at RXBnSIDH */
#define MCP_WRITE       0x02u
#define MCP_RTS(n)      (0x80u | (1u << (n))) /* request to send TXBn */
#define MCP_READ_STATUS 0xA0u
#define MCP_BIT_MODIFY  0x05u

/* Registers */
#define MCP_RXF0SIDH   0x00u /* RXF0..RXF2 at 0x00/0x04/0x08, RXF3..RXF5 at 0x10/0x14/0x18 */
#define MCP_RXF3SIDH   0x10u
#define MCP_CANSTAT    0x0Eu
#define MCP_CANCTRL    0x0Fu
#define MCP_TEC        0x1Cu
#define MCP_REC        0x1Du
#define MCP_RXM0SIDH   0x20u /* RXM0 at 0x20, RXM1 at 0x24 */
#define MCP_CNF3       0x28u /* CNF3, CNF2, CNF1, CANINTE, CANINTF, EFLG follow at 0x29..0x2D */
#define MCP_CANINTE    0x2Bu
#define MCP_CANINTF    0x2Cu
#define MCP_EFLG       0x2Du
#define MCP_TXBCTRL(n) (0x30u + 0x10u * (uint8_t)(n))
#define MCP_RXB0CTRL   0x60u
#define MCP_RXB1CTRL   0x70u

/* CANCTRL / CANSTAT */
#define MCP_REQOP_NORMAL   0x00u
#define MCP_REQOP_LOOPBACK 0x40u
#define MCP_REQOP_LISTEN   0x60u
#define MCP_REQOP_CONFIG   0x80u
#define MCP_REQOP_MASK     0xE0u /* also OPMOD in CANSTAT */
#define MCP_ABAT           0x10u

/* CANINTE / CANINTF */
#define MCP_RX0IF 0x01u
#define MCP_RX1IF 0x02u
#define MCP_TX0IF 0x04u /* TXnIF = TX0IF << n */
#define MCP_TXIF  0x1Cu
#define MCP_ERRIF 0x20u
#define MCP_WAKIF 0x40u
#define MCP_MERRF 0x80u

/* EFLG */
#define MCP_RX1OVR 0x80u
#define MCP_RX0OVR 0x40u
#define MCP_TXBO   0x20u
#define MCP_TXEP   0x10u
#define MCP_RXEP   0x08u

/* TXBnCTRL */
#define MCP_TXREQ 0x08u
#define MCP_TXP   0x03u

/* RXBnCTRL */
#define MCP_RXM_ANY 0x60u /* RXM = 11: masks and filters off */
#define MCP_BUKT    0x04u

/* Identifier registers (TXBnSIDL, RXBnSIDL) and DLC */
#define MCP_SIDL_SRR   0x10u /* RXBnSIDL: standard remote frame */
#define MCP_SIDL_EXIDE 0x08u /* TXBnSIDL EXIDE, RXBnSIDL IDE */
#define MCP_DLC_RTR    0x40u

#endif
