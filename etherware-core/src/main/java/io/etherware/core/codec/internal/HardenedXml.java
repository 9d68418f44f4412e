package io.etherware.core.codec.internal;

import com.ctc.wstx.api.WstxInputProperties;
import com.ctc.wstx.api.WstxOutputProperties;
import io.etherware.core.message.MessageFormatException;
import org.codehaus.stax2.XMLInputFactory2;
import org.codehaus.stax2.XMLStreamReader2;
import org.codehaus.stax2.io.Stax2ByteArraySource;

import javax.xml.stream.XMLInputFactory;
import javax.xml.stream.XMLOutputFactory;
import javax.xml.stream.XMLResolver;
import javax.xml.stream.XMLStreamConstants;
import javax.xml.stream.XMLStreamException;
import java.io.StringReader;
import java.util.Locale;

/**
 * The Woodstox StAX factories behind the codec's Jackson mapper, configured against hostile
 * input, and the vetting of a document's prolog before Jackson sees it.
 *
 * <p>Input: no DTD processing, no external entities, every resolver refusing, and Woodstox's
 * limits on element depth, text length and attribute size and count. A document is opened here,
 * its prolog read up to the root element: a {@code <!DOCTYPE>} of any kind, an encoding other
 * than UTF-8 or a root other than {@code <message>} is rejected before anything else is read, so
 * an entity is never declared, let alone expanded or fetched.
 *
 * <p>The factories are configured once and then only used to create readers and writers, which
 * Woodstox documents as thread-safe; so is this class.
 */
public final class HardenedXml {

    /** Attributes we write: {@code version}, {@code type}, {@code xsi:nil} and its namespace. */
    private static final int MAX_ATTRIBUTES_PER_ELEMENT = 16;

    private final XMLInputFactory2 inputFactory;
    private final XMLOutputFactory outputFactory;

    public HardenedXml(int maxNestingDepth, int maxTextLength) {
        inputFactory = woodstox("com.ctc.wstx.stax.WstxInputFactory", XMLInputFactory2.class);
        inputFactory.setProperty(XMLInputFactory.SUPPORT_DTD, false);
        inputFactory.setProperty(XMLInputFactory.IS_SUPPORTING_EXTERNAL_ENTITIES, false);
        inputFactory.setProperty(XMLInputFactory.IS_NAMESPACE_AWARE, true);
        inputFactory.setProperty(XMLInputFactory.IS_COALESCING, true);
        inputFactory.setProperty(XMLInputFactory.IS_VALIDATING, false);
        XMLResolver refuse = (publicId, systemId, baseUri, namespace) -> {
            throw new XMLStreamException("external reference '" + systemId + "' refused");
        };
        inputFactory.setXMLResolver(refuse);
        inputFactory.setProperty(WstxInputProperties.P_DTD_RESOLVER, refuse);
        inputFactory.setProperty(WstxInputProperties.P_ENTITY_RESOLVER, refuse);
        inputFactory.setProperty(WstxInputProperties.P_UNDECLARED_ENTITY_RESOLVER, null);
        inputFactory.setProperty(WstxInputProperties.P_MAX_ELEMENT_DEPTH, maxNestingDepth);
        inputFactory.setProperty(WstxInputProperties.P_MAX_TEXT_LENGTH, maxTextLength);
        inputFactory.setProperty(WstxInputProperties.P_MAX_ATTRIBUTE_SIZE, maxTextLength);
        inputFactory.setProperty(WstxInputProperties.P_MAX_ATTRIBUTES_PER_ELEMENT, MAX_ATTRIBUTES_PER_ELEMENT);

        outputFactory = woodstox("com.ctc.wstx.stax.WstxOutputFactory", XMLOutputFactory.class);
        outputFactory.setProperty(XMLOutputFactory.IS_REPAIRING_NAMESPACES, true);
        // A CR in text must survive the reader's line-end normalization, so it goes out as &#xd;.
        outputFactory.setProperty(WstxOutputProperties.P_OUTPUT_ESCAPE_CR, true);
    }

    /**
     * Woodstox by name, never whichever StAX implementation a service lookup finds: the limits
     * set here are Woodstox properties. Not imported because its factory classes carry a bnd
     * annotation whose class is not on our compile path, and javac would warn on every build.
     */
    private static <T> T woodstox(String className, Class<T> type) {
        try {
            return type.cast(Class.forName(className).getConstructor().newInstance());
        } catch (ReflectiveOperationException | ClassCastException e) {
            throw new IllegalStateException("the message codec needs Woodstox (com.fasterxml.woodstox:woodstox-core, "
                    + "a dependency of jackson-dataformat-xml): cannot create " + className, e);
        }
    }

    public XMLInputFactory inputFactory() {
        return inputFactory;
    }

    public XMLOutputFactory outputFactory() {
        return outputFactory;
    }

    /**
     * Opens a UTF-8 document and reads its prolog; the reader is left on the root element.
     *
     * @throws MessageFormatException for invalid UTF-8, a DOCTYPE, another encoding or a wrong root
     * @throws XMLStreamException     for malformed XML, translated by {@link CodecErrors}
     */
    public XMLStreamReader2 open(byte[] document) throws XMLStreamException {
        Utf8.requireValid(document);
        var reader = (XMLStreamReader2) inputFactory.createXMLStreamReader(
                new Stax2ByteArraySource(document, 0, document.length));
        try {
            requireUtf8(reader.getEncoding(), "detected");
            requireUtf8(reader.getCharacterEncodingScheme(), "declared");
            return toRoot(reader);
        } catch (RuntimeException | XMLStreamException e) {
            closeQuietly(reader);
            throw e;
        }
    }

    /** Opens a document given as text (no encoding applies) and reads its prolog. */
    public XMLStreamReader2 open(String document) throws XMLStreamException {
        var reader = (XMLStreamReader2) inputFactory.createXMLStreamReader(new StringReader(document));
        try {
            return toRoot(reader);
        } catch (RuntimeException | XMLStreamException e) {
            closeQuietly(reader);
            throw e;
        }
    }

    private static XMLStreamReader2 toRoot(XMLStreamReader2 reader) throws XMLStreamException {
        while (true) {
            int event = reader.next();
            switch (event) {
                case XMLStreamConstants.START_ELEMENT -> {
                    String namespace = reader.getNamespaceURI();
                    if (!Wire.MESSAGE.equals(reader.getLocalName()) || namespace != null && !namespace.isEmpty()) {
                        throw new MessageFormatException("root element is <" + reader.getPrefixedName() + ">"
                                + (namespace == null || namespace.isEmpty() ? "" : " in namespace '" + namespace + "'")
                                + "; a message is a <" + Wire.MESSAGE + "> element in no namespace");
                    }
                    return reader;
                }
                case XMLStreamConstants.DTD -> throw new MessageFormatException(
                        "DOCTYPE is not allowed: a message has no DTD, so no entity is declared, expanded or fetched");
                case XMLStreamConstants.COMMENT, XMLStreamConstants.SPACE, XMLStreamConstants.PROCESSING_INSTRUCTION -> {
                    // allowed in the prolog
                }
                default -> throw new MessageFormatException("unexpected content before the root element (StAX event "
                        + event + ")");
            }
        }
    }

    private static void requireUtf8(String encoding, String how) {
        if (encoding == null) {
            return;
        }
        String normalized = encoding.replace("-", "").replace("_", "").toUpperCase(Locale.ROOT);
        if (!normalized.equals("UTF8")) {
            throw new MessageFormatException(how + " encoding '" + encoding + "' is not accepted; messages are UTF-8");
        }
    }

    public static void closeQuietly(XMLStreamReader2 reader) {
        try {
            reader.closeCompletely();
        } catch (XMLStreamException | RuntimeException ignored) {
            // closing after a failure: the failure is what gets reported
        }
    }
}
