/* Vocabulary descriptors of the types of ext_types.h, as a generated vocabulary.c defines them
 * (contract/vocabulary.h): shared by test_ext_types.c and the control tool control_echo.c. */
#ifndef EXT_TYPES_VOCABULARY_H
#define EXT_TYPES_VOCABULARY_H
#include <stddef.h>
#include "contract/vocabulary.h"
#include "ext_types.h"

static const ContractEnumMember mode_members[] = { { "IDLE", XMode_IDLE }, { "TELEOP", XMode_TELEOP }, { "AUTO", XMode_AUTO } };
__attribute__((unused)) static const ContractType t_mode = CONTRACT_ENUM_TYPE(XMode, mode_members, 3, NULL);
__attribute__((unused)) static const ContractType t_row = CONTRACT_ARRAY_TYPE("float[3]", double[3], contract_type_double, 3, NULL);
__attribute__((unused)) static const ContractType t_mat = CONTRACT_ARRAY_TYPE("float[3][3]", double[3][3], t_row, 3, NULL);
__attribute__((unused)) static const ContractType t_ranges = CONTRACT_ARRAY_TYPE("float[180]", double[180], contract_type_double, 180, NULL);
static const ContractField cell_fields[] = { { "id", offsetof(XCell, id), &contract_type_long },
                                             { "w", offsetof(XCell, w), &contract_type_double },
                                             { "tag", offsetof(XCell, tag), &contract_type_string } };
__attribute__((unused)) static const ContractType t_cell = { .name = "XCell", .kind = CONTRACT_KIND_STRUCT, .size = sizeof(XCell),
                                     .nfields = 3, .fields = cell_fields };
__attribute__((unused)) static const ContractType t_cells4 = CONTRACT_ARRAY_TYPE("XCell[4]", XCell[4], t_cell, 4, NULL);
__attribute__((unused)) static const ContractType t_cells2 = CONTRACT_ARRAY_TYPE("XCell[2]", XCell[2], t_cell, 2, NULL);
static const ContractField scan_fields[] = { { "ranges", offsetof(XScan, ranges), &t_ranges },
                                             { "mode", offsetof(XScan, mode), &t_mode },
                                             { "ok", offsetof(XScan, ok), &contract_type_bool },
                                             { "cells", offsetof(XScan, cells), &t_cells2 },
                                             { "m", offsetof(XScan, m), &t_mat } };
__attribute__((unused)) static const ContractType t_scan = { .name = "XScan", .kind = CONTRACT_KIND_STRUCT, .size = sizeof(XScan),
                                     .nfields = 5, .fields = scan_fields };
#endif
