package io.etherware.core.codec;

import com.fasterxml.jackson.core.JsonToken;
import com.fasterxml.jackson.core.StreamReadConstraints;
import com.fasterxml.jackson.databind.ObjectReader;
import com.fasterxml.jackson.databind.ObjectWriter;
import com.fasterxml.jackson.databind.module.SimpleModule;
import com.fasterxml.jackson.dataformat.xml.XmlFactory;
import com.fasterxml.jackson.dataformat.xml.XmlMapper;
import com.fasterxml.jackson.dataformat.xml.deser.FromXmlParser;
import com.fasterxml.jackson.dataformat.xml.ser.ToXmlGenerator;
import io.etherware.core.codec.internal.CodecErrors;
import io.etherware.core.codec.internal.EnvelopeDeserializer;
import io.etherware.core.codec.internal.EnvelopeSerializer;
import io.etherware.core.codec.internal.HardenedXml;
import io.etherware.core.message.ContentsTypes;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageFormatException;
import org.codehaus.stax2.XMLStreamReader2;

import java.nio.charset.StandardCharsets;
import java.util.Objects;

/**
 * Encodes {@link Message}s to the Etherware XML wire format and decodes them back; see
 * {@code WIRE-FORMAT.md} and the schema {@code io/etherware/core/codec/etherware-message.xsd}.
 *
 * <p>Round trips are exact: {@code decode(encode(m)).equals(m)} for every message whose strings
 * XML 1.0 can carry (no control characters other than tab, LF and CR, no U+FFFE/U+FFFF, no
 * unpaired surrogates) and that fits the limits. The encoder refuses anything the decoder with the
 * same limits would reject, so what one node encodes, a node with the same limits decodes.
 *
 * <p>Decoding treats its input as hostile: a DOCTYPE (hence any entity declaration, external
 * entity or "billion laughs"), an encoding other than UTF-8, invalid UTF-8, a document over
 * {@link #maxDocumentBytes()}, nesting deeper than {@link #maxNestingDepth()} or a text over
 * {@link #maxTextLength()} is rejected before it can cost much. Contents are instantiated only
 * from types registered in the codec's {@link ContentsTypes}, by name; there is no Jackson
 * default typing and no class name on the wire. Every failure, of either direction, is a
 * {@link MessageFormatException} whose message says what was wrong and where; no Jackson or
 * Woodstox exception escapes.
 *
 * <p><b>Records on the module path.</b> The codec reads and builds contents records by
 * reflection from module {@code io.etherware.core} (not through Jackson's databind). A public
 * record in an exported package works as it is; otherwise open its package to the codec:
 * {@code opens com.example.messages to io.etherware.core;}. On the class path nothing is needed.
 *
 * <p><b>Threading.</b> Immutable and thread-safe: one instance per node serves every thread.
 * It holds one configured {@link XmlMapper} and reuses its immutable {@link ObjectReader} and
 * {@link ObjectWriter}; each call streams through the document without building a tree. A call
 * takes a few microseconds and allocates a few kilobytes (parser state, the output, the decoded
 * strings), and it does not block: fine at the edge of a node (network, snapshots), but not
 * something to put in a control loop's hot path. In-process delivery never encodes.
 */
public final class MessageCodec {

    /** Default {@link #maxDocumentBytes()}: 1 MiB. */
    public static final int DEFAULT_MAX_DOCUMENT_BYTES = 1 << 20;
    /** Default {@link #maxNestingDepth()}: elements, counting {@code <message>} as 1. */
    public static final int DEFAULT_MAX_NESTING_DEPTH = 64;
    /** Default {@link #maxTextLength()}: 512 Ki characters. */
    public static final int DEFAULT_MAX_TEXT_LENGTH = 512 * 1024;

    static final int MIN_DOCUMENT_BYTES = 256;
    static final int MAX_DOCUMENT_BYTES = 256 << 20;
    static final int MIN_NESTING_DEPTH = 3;
    static final int MAX_NESTING_DEPTH = 1000;
    static final int MIN_TEXT_LENGTH = 64;

    private final ContentsTypes contentsTypes;
    private final int maxDocumentBytes;
    private final int maxNestingDepth;
    private final int maxTextLength;
    private final HardenedXml xml;
    private final CodecErrors errors;
    private final XmlFactory xmlFactory;
    private final ObjectReader reader;
    private final ObjectWriter writer;

    /**
     * A codec with the default limits over {@code types}.
     *
     * @param types the contents types it carries, e.g. a node's {@code Kernel.contentsTypes()}
     */
    public MessageCodec(ContentsTypes types) {
        this(builder().contentsTypes(types));
    }

    private MessageCodec(Builder builder) {
        contentsTypes = builder.contentsTypes;
        maxDocumentBytes = builder.maxDocumentBytes;
        maxNestingDepth = builder.maxNestingDepth;
        maxTextLength = builder.maxTextLength;
        xml = new HardenedXml(maxNestingDepth, maxTextLength);
        errors = new CodecErrors(maxNestingDepth, maxTextLength);
        xmlFactory = XmlFactory.builder()
                .xmlInputFactory(xml.inputFactory())
                .xmlOutputFactory(xml.outputFactory())
                .enable(ToXmlGenerator.Feature.WRITE_NULLS_AS_XSI_NIL)
                .enable(FromXmlParser.Feature.PROCESS_XSI_NIL)
                .disable(FromXmlParser.Feature.EMPTY_ELEMENT_AS_NULL)
                .disable(ToXmlGenerator.Feature.WRITE_XML_DECLARATION)
                // Woodstox enforces our limits first, with clearer messages; Jackson's are a backstop.
                .streamReadConstraints(StreamReadConstraints.builder()
                        .maxNestingDepth(maxNestingDepth + 1)
                        .maxStringLength(Math.max(maxTextLength, StreamReadConstraints.DEFAULT_MAX_STRING_LEN))
                        .build())
                .build();
        var module = new SimpleModule("etherware-message");
        module.addSerializer(Message.class, new EnvelopeSerializer(contentsTypes, maxNestingDepth, maxTextLength));
        module.addDeserializer(Message.class, new EnvelopeDeserializer(contentsTypes, maxTextLength));
        XmlMapper mapper = XmlMapper.builder(xmlFactory).addModule(module).build();
        writer = mapper.writerFor(Message.class).withRootName("message");
        reader = mapper.readerFor(Message.class);
    }

    /** {@return a builder starting from the defaults} */
    public static Builder builder() {
        return new Builder();
    }

    /**
     * The message as a UTF-8 XML document.
     *
     * @param message the message to encode; its {@link Message#origin()} is not written
     * @return the document, without an XML declaration, at most {@link #maxDocumentBytes()} long
     * @throws MessageFormatException if its contents type is not registered, a string holds a
     *                                character XML cannot carry, or it exceeds a limit
     */
    public byte[] encode(Message message) {
        Objects.requireNonNull(message, "message");
        byte[] document;
        try {
            document = writer.writeValueAsBytes(message);
        } catch (Exception e) {
            throw errors.encodeFailure(message.messageId(), e);
        }
        if (document.length > maxDocumentBytes) {
            throw new MessageFormatException("cannot encode message " + message.messageId() + ": its document is "
                    + document.length + " bytes, over maxDocumentBytes=" + maxDocumentBytes);
        }
        return document;
    }

    /**
     * The message as an XML document in a String; the same document as {@link #encode}.
     *
     * @param message the message to encode
     * @return the document as text
     * @throws MessageFormatException for the reasons of {@link #encode}
     */
    public String encodeToString(Message message) {
        return new String(encode(message), StandardCharsets.UTF_8);
    }

    /**
     * The message in a UTF-8 XML document.
     *
     * @param document the document's bytes, from an untrusted peer
     * @return the decoded message, without an origin (the network layer sets it)
     * @throws MessageFormatException saying what is wrong with the document
     */
    public Message decode(byte[] document) {
        Objects.requireNonNull(document, "document");
        if (document.length > maxDocumentBytes) {
            throw new MessageFormatException("document of " + document.length + " bytes is over maxDocumentBytes="
                    + maxDocumentBytes);
        }
        XMLStreamReader2 stax = null;
        try {
            stax = xml.open(document);
            return read(stax);
        } catch (Exception e) {
            throw errors.decodeFailure(e);
        } finally {
            if (stax != null) {
                HardenedXml.closeQuietly(stax);
            }
        }
    }

    /**
     * The message in an XML document given as text. The size limit counts its chars, which are
     * never more than its UTF-8 bytes.
     *
     * @param document the document, from an untrusted source
     * @return the decoded message, without an origin
     * @throws MessageFormatException saying what is wrong with the document
     */
    public Message decode(String document) {
        Objects.requireNonNull(document, "document");
        if (document.length() > maxDocumentBytes) {
            throw new MessageFormatException("document of " + document.length() + " chars is over maxDocumentBytes="
                    + maxDocumentBytes);
        }
        XMLStreamReader2 stax = null;
        try {
            stax = xml.open(document);
            return read(stax);
        } catch (Exception e) {
            throw errors.decodeFailure(e);
        } finally {
            if (stax != null) {
                HardenedXml.closeQuietly(stax);
            }
        }
    }

    private Message read(XMLStreamReader2 stax) throws Exception {
        try (FromXmlParser parser = xmlFactory.createParser(stax)) {
            Message message = reader.readValue(parser);
            if (message == null) {
                // xsi:nil on the root: Jackson maps it to null without asking our deserializer.
                throw new MessageFormatException("<message> must not be nil");
            }
            // Read to the end, so trailing garbage or a second root is an error, not ignored.
            JsonToken trailing = parser.nextToken();
            if (trailing != null) {
                throw new MessageFormatException("unexpected content after </message>: " + trailing);
            }
            return message;
        }
    }

    /** {@return the registry contents types are looked up in} */
    public ContentsTypes contentsTypes() {
        return contentsTypes;
    }

    /** {@return the largest document, in bytes, that is encoded or decoded} */
    public int maxDocumentBytes() {
        return maxDocumentBytes;
    }

    /** {@return the deepest element nesting accepted, {@code <message>} counting as 1} */
    public int maxNestingDepth() {
        return maxNestingDepth;
    }

    /** {@return the longest text (element content or attribute value) accepted, in chars} */
    public int maxTextLength() {
        return maxTextLength;
    }

    @Override
    public String toString() {
        return "MessageCodec[maxDocumentBytes=" + maxDocumentBytes + ", maxNestingDepth=" + maxNestingDepth
                + ", maxTextLength=" + maxTextLength + ", types=" + contentsTypes.names() + "]";
    }

    /**
     * Configures a {@link MessageCodec}; validated once, in {@link #build()}. Not thread-safe;
     * use it on one thread, then share the codec.
     */
    public static final class Builder {
        private ContentsTypes contentsTypes = new ContentsTypes();
        private int maxDocumentBytes = DEFAULT_MAX_DOCUMENT_BYTES;
        private int maxNestingDepth = DEFAULT_MAX_NESTING_DEPTH;
        private int maxTextLength = DEFAULT_MAX_TEXT_LENGTH;

        private Builder() {
        }

        /**
         * The registry of contents types; default a new one with only the built-in types. Give the
         * node's ({@code Kernel.contentsTypes()}) for a codec that carries a node's messages.
         *
         * @param types the registry decoding instantiates from and encoding names types by
         * @return this builder
         */
        public Builder contentsTypes(ContentsTypes types) {
            this.contentsTypes = Objects.requireNonNull(types, "contentsTypes");
            return this;
        }

        /**
         * Largest document in bytes; default 1 MiB.
         *
         * @param bytes the limit, 256 B to 256 MiB (checked by {@link #build()})
         * @return this builder
         */
        public Builder maxDocumentBytes(int bytes) {
            this.maxDocumentBytes = bytes;
            return this;
        }

        /**
         * Deepest element nesting, {@code <message>} counting as 1; default 64.
         *
         * @param depth the limit, 3 to 1000 (checked by {@link #build()})
         * @return this builder
         */
        public Builder maxNestingDepth(int depth) {
            this.maxNestingDepth = depth;
            return this;
        }

        /**
         * Longest text or attribute value in chars; default 512 Ki.
         *
         * @param chars the limit, 64 to 256 Mi (checked by {@link #build()})
         * @return this builder
         */
        public Builder maxTextLength(int chars) {
            this.maxTextLength = chars;
            return this;
        }

        /**
         * Validates the settings and builds the codec.
         *
         * @return a new, immutable codec
         * @throws IllegalArgumentException naming the setting and its value if one is out of range
         */
        public MessageCodec build() {
            requireRange("maxDocumentBytes", maxDocumentBytes, MIN_DOCUMENT_BYTES, MAX_DOCUMENT_BYTES);
            requireRange("maxNestingDepth", maxNestingDepth, MIN_NESTING_DEPTH, MAX_NESTING_DEPTH);
            requireRange("maxTextLength", maxTextLength, MIN_TEXT_LENGTH, MAX_DOCUMENT_BYTES);
            return new MessageCodec(this);
        }

        private static void requireRange(String field, int value, int min, int max) {
            if (value < min || value > max) {
                throw new IllegalArgumentException(field + "=" + value + " must be in [" + min + ", " + max + "]");
            }
        }
    }
}
