package io.etherware.core.message;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.CsvSource;
import org.junit.jupiter.params.provider.ValueSource;

import java.util.LinkedHashMap;
import java.util.List;
import java.util.Random;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNotEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

class ProfileTest {

    @Test
    void shouldParseRoleAndAttributesInOrder() {
        Profile profile = Profile.parse("controller[car=1,loop=inner]");
        assertEquals("controller", profile.role());
        assertEquals(List.of("car", "loop"), List.copyOf(profile.attributes().keySet()));
        assertEquals("1", profile.attributes().get("car"));
        assertEquals("inner", profile.attributes().get("loop"));
        assertTrue(Profile.parse("notifier").attributes().isEmpty());
    }

    @ParameterizedTest
    @ValueSource(strings = {"controller", "controller[car=1]", "controller[car=1,loop=inner]", "a.b-c_d[k=v:/@+-._]",
            "0[1=2]", "node-1.local[ip=10.0.0.1:8080,path=/x/y]"})
    void shouldFormatBackExactlyWhenParsed(String text) {
        assertEquals(text, Profile.parse(text).toString());
    }

    @Test
    void shouldParseAndFormatAsExactInversesWhenProfilesAreRandom() {
        var random = new Random(7);
        String nameChars = "abcXYZ019_.-";
        String valueChars = "abcXYZ019_.:/@+-";
        for (int i = 0; i < 2_000; i++) {
            var attributes = new LinkedHashMap<String, String>();
            int count = random.nextInt(5);
            while (attributes.size() < count) {
                attributes.put(word(random, "k_", nameChars), word(random, valueChars, valueChars));
            }
            var profile = new Profile(word(random, "r_", nameChars), attributes);
            Profile parsed = Profile.parse(profile.toString());
            assertEquals(profile, parsed);
            assertEquals(profile.toString(), parsed.toString());
            assertEquals(List.copyOf(profile.attributes().keySet()), List.copyOf(parsed.attributes().keySet()));
        }
    }

    @ParameterizedTest
    @CsvSource(delimiter = '|', value = {
            "''                     | role ''",
            "'[car=1]'              | role ''",
            "'con troller'          | role 'con troller'",
            "'.controller'          | role '.controller'",
            "'controller['          | without closing",
            "'controller[car=1'     | without closing",
            "'controller[car=1]x'   | without closing",
            "'controller[]'         | empty attribute list",
            "'controller[car]'      | attribute 'car' is not key=value",
            "'controller[car=]'     | attribute value '' of 'car'",
            "'controller[=1]'       | attribute key ''",
            "'controller[car=1,]'   | attribute '' is not key=value",
            "'controller[car=a b]'  | attribute value 'a b' of 'car'",
            "'controller[car=1,car=2]' | attribute 'car' given twice",
            "'controller[a=1][b=2]' | attribute value '1][b=2' of 'a'",
    })
    void shouldNameTheTextAndTheProblemWhenMalformed(String text, String expected) {
        var error = assertThrows(IllegalArgumentException.class, () -> Profile.parse(text));
        assertTrue(error.getMessage().contains(expected), error.getMessage());
        assertTrue(error.getMessage().contains("'" + text + "'"), "names the text: " + error.getMessage());
    }

    @Test
    void shouldBeEqualWhateverTheAttributeOrder() {
        Profile ab = Profile.parse("controller[a=1,b=2]");
        Profile ba = Profile.parse("controller[b=2,a=1]");
        assertEquals(ab, ba);
        assertEquals(ab.hashCode(), ba.hashCode());
        assertNotEquals(ab.toString(), ba.toString(), "order is kept for display");
        assertNotEquals(ab, Profile.parse("controller[a=1,b=3]"));
        assertNotEquals(ab, Profile.parse("observer[a=1,b=2]"));
        assertNotEquals(ab, Profile.parse("controller[a=1]"));
    }

    @Test
    void shouldMatchAQueryWhenEveryQueriedAttributeIsEqual() {
        Profile controller = Profile.parse("controller[car=1,loop=inner]");
        assertTrue(controller.matches(Profile.parse("controller")));
        assertTrue(controller.matches(Profile.parse("controller[car=1]")));
        assertTrue(controller.matches(Profile.parse("controller[loop=inner,car=1]")));
        assertFalse(controller.matches(Profile.parse("controller[car=2]")));
        assertFalse(controller.matches(Profile.parse("controller[car=1,mode=x]")));
        assertFalse(controller.matches(Profile.parse("observer[car=1]")));
        assertFalse(Profile.parse("controller").matches(controller), "a query with more attributes does not match");
    }

    @Test
    void shouldAppendOrReplaceAnAttributeWhenAskedWith() {
        Profile base = Profile.parse("controller[car=1]");
        assertEquals("controller[car=1,loop=inner]", base.with("loop", "inner").toString());
        assertEquals("controller[car=2]", base.with("car", "2").toString());
        assertEquals("controller[car=1]", base.toString(), "immutable");
        assertThrows(IllegalArgumentException.class, () -> base.with("bad key", "1"));
        assertThrows(IllegalArgumentException.class, () -> base.with("k", "bad value"));
    }

    @Test
    void shouldBuildFromKeyValuePairsAndRejectOddOrRepeatedOnes() {
        assertEquals(Profile.parse("controller[car=1,loop=inner]"), Profile.of("controller", "car", "1", "loop", "inner"));
        var odd = assertThrows(IllegalArgumentException.class, () -> Profile.of("controller", "car"));
        assertTrue(odd.getMessage().contains("key/value pairs"), odd.getMessage());
        var twice = assertThrows(IllegalArgumentException.class, () -> Profile.of("c", "k", "1", "k", "2"));
        assertTrue(twice.getMessage().contains("'k' given twice"), twice.getMessage());
    }

    @Test
    void shouldKeepAttributesUnmodifiable() {
        var attributes = new LinkedHashMap<String, String>();
        attributes.put("car", "1");
        Profile profile = new Profile("controller", attributes);
        attributes.put("car", "2");
        assertEquals("1", profile.attributes().get("car"), "a copy is kept");
        assertThrows(UnsupportedOperationException.class, () -> profile.attributes().put("x", "y"));
    }

    private static String word(Random random, String first, String rest) {
        var word = new StringBuilder().append(first.charAt(random.nextInt(first.length())));
        for (int i = random.nextInt(6); i > 0; i--) {
            word.append(rest.charAt(random.nextInt(rest.length())));
        }
        return word.toString();
    }
}
