package io.etherware.core.message;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.CsvSource;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

class MessageIdTest {

    @Test
    void shouldParseNodeAndSequence() {
        MessageId id = MessageId.parse("node-1.local#42");
        assertEquals("node-1.local", id.nodeId());
        assertEquals(42, id.sequence());
        assertEquals(new MessageId("n", Long.MAX_VALUE), MessageId.parse("n#9223372036854775807"));
    }

    @Test
    void shouldFormatBackExactlyWhenParsed() {
        for (String text : new String[]{"n#0", "node1#1042", "a_b.c-d#9223372036854775807"}) {
            assertEquals(text, MessageId.parse(text).toString());
        }
    }

    @ParameterizedTest
    @CsvSource(delimiter = '|', value = {
            "''                        | is not of the form node#sequence",
            "'node'                    | is not of the form node#sequence",
            "'#1'                      | is not of the form node#sequence",
            "'node#'                   | is not of the form node#sequence",
            "'node#x'                  | sequence that is not a number",
            "'node#9223372036854775808' | sequence that is not a number",
            "'node#-1'                 | sequence=-1 must be >= 0",
            "'no de#1'                 | nodeId='no de'",
            "'a#b#1'                   | nodeId='a#b'",
    })
    void shouldSayWhatIsWrongWhenMalformed(String text, String expected) {
        var error = assertThrows(IllegalArgumentException.class, () -> MessageId.parse(text));
        assertTrue(error.getMessage().contains(expected), error.getMessage());
    }
}
