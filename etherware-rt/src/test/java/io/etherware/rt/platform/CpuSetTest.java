package io.etherware.rt.platform;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import org.junit.jupiter.api.Test;

class CpuSetTest {

    @Test
    void shouldParseRangesAndPrintThemCompactlyWhenGivenTasksetSyntax() {
        CpuSet set = CpuSet.parse("3, 0-1,5-6");
        assertArrayEquals(new int[] {0, 1, 3, 5, 6}, set.cpus());
        assertEquals("0-1,3,5-6", set.toString());
        assertEquals(set, CpuSet.parse(set.toString()));
    }

    @Test
    void shouldMeanInheritWhenEmpty() {
        assertTrue(CpuSet.parse("").isInherit());
        assertTrue(CpuSet.parse("inherit").isInherit());
        assertEquals("inherit", CpuSet.inherit().toString());
    }

    @Test
    void shouldNameTheBadPartWhenTextIsMalformed() {
        var error = assertThrows(IllegalArgumentException.class, () -> CpuSet.parse("0-1,x"));
        assertTrue(error.getMessage().contains("'x'"), error.getMessage());
        var range = assertThrows(IllegalArgumentException.class, () -> CpuSet.parse("3-1"));
        assertTrue(range.getMessage().contains("3-1"), range.getMessage());
        assertThrows(IllegalArgumentException.class, () -> CpuSet.of(1024));
        assertThrows(IllegalArgumentException.class, () -> CpuSet.of());
    }
}
