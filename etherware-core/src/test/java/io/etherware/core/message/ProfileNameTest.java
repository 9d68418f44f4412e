package io.etherware.core.message;

import static org.junit.jupiter.api.Assertions.assertEquals;

import java.util.List;
import java.util.regex.Pattern;
import org.junit.jupiter.api.Test;

/** {@link Profile#isName} accepts exactly the language of {@link Profile#NAME_PATTERN}. */
class ProfileNameTest {

    @Test
    void shouldAgreeWithTheNamePatternWhenCheckingNames() {
        Pattern pattern = Pattern.compile(Profile.NAME_PATTERN);
        var samples = List.of("", "a", "Z", "0", "_", ".", "-", "a.b", "a-b", "plant-1", "node_7", ".a", "-a", "a b",
                "a/b", "é", "a:b", "a..", "9-.", "x[", "A_Z.0-9");
        for (String sample : samples) {
            assertEquals(pattern.matcher(sample).matches(), Profile.isName(sample), "for '" + sample + "'");
        }
        // Every single character and every pair of printable ASCII characters.
        for (char first = ' '; first <= '~'; first++) {
            String one = String.valueOf(first);
            assertEquals(pattern.matcher(one).matches(), Profile.isName(one), "for '" + one + "'");
            for (char second = ' '; second <= '~'; second++) {
                String two = one + second;
                assertEquals(pattern.matcher(two).matches(), Profile.isName(two), "for '" + two + "'");
            }
        }
        assertEquals(false, Profile.isName(null));
    }
}
